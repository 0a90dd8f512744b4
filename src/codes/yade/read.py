# millimpact deck: a user's YADE script run by YADE's own Python up to the end of its set-up,
# then what YADE holds dumped as JSON for the Rust reader (src/codes/yade/deck.rs). Run by the
# launcher's Python as `python3 read.py SCRIPT DUMP` in a scratch folder; writes DUMP and
# prints nothing the reader needs but its `MILLIMPACT` lines.
#
# Everything that advances the simulation is disarmed: the first call of O.run, O.step,
# O.wait or O.runEngine ends the reading there (the state at that call is dumped, and the line
# of the call is named); O.save writes nothing. An exception of the script is printed as one
# `MILLIMPACT raised` line with the script's line, and nothing is dumped.
import json
import math
import os
import sys
import traceback

if "yade" not in sys.modules:
    # `yade.runtime` imports IPython only to read its version for the launcher's shell, which
    # this reading never opens (the same stand-in as a batch's, src/codes/yade/batch.rs).
    import types

    shell = types.ModuleType("IPython")
    shell.__version__ = "0.0"
    sys.modules["IPython"] = shell
    import yade

    del sys.modules["IPython"]
import yade
import yade.wrapper as wrapper


class Inert(object):
    """What the GUI gives a script read headless: anything asked of it is another Inert, any
    call returns one, any value set on it is kept nowhere."""

    def __getattr__(self, name):
        return Inert()

    def __setattr__(self, name, value):
        pass

    def __call__(self, *args, **kwargs):
        return Inert()

    def __getitem__(self, key):
        return Inert()

    def __iter__(self):
        return iter(())

    def __len__(self):
        return 0


class InertModule(type(sys)):
    """`yade.qt` read headless, as `O.run` is disarmed: `import yade.qt`, `from yade import qt`,
    `qt.View()`, `qt.Controller()` and whatever they hold do nothing, and the set-up goes on."""

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return Inert()


sys.modules["yade.qt"] = InertModule("yade.qt")
yade.qt = sys.modules["yade.qt"]

SCRIPT = os.path.abspath(sys.argv[1])
DUMP = sys.argv[2]


class StopReading(BaseException):
    """The script asked to advance the simulation: its set-up ends here. A BaseException, so
    that the script's own `except Exception` does not catch it."""

    def __init__(self, call):
        BaseException.__init__(self, call)
        self.call = call


def script_line():
    """The line of the user's script that is running now (the innermost frame in its file)."""
    line = None
    for frame in traceback.extract_stack():
        if os.path.abspath(frame.filename) == SCRIPT:
            line = frame.lineno
    return line


def disarm(name):
    def stop(*args, **kwargs):
        raise StopReading("O." + name)

    setattr(wrapper.Omega, name, stop)


for name in ("run", "step", "wait", "runEngine"):
    disarm(name)

saved = []


def save(*args, **kwargs):
    saved.append(script_line())


wrapper.Omega.save = save

# Where the script appends its materials and bodies and sets its engines and step.
material_lines = {}
body_lines = {}
set_lines = {}
appended_values = {}


def remember(lines, ids):
    line = script_line()
    for i in ids if isinstance(ids, (list, tuple)) else [ids]:
        if isinstance(i, int) and i not in lines:
            lines[i] = line
    return ids


original_material_append = wrapper.MaterialContainer.append
original_body_append = wrapper.BodyContainer.append


def material_append(self, *args, **kwargs):
    ids = remember(material_lines, original_material_append(self, *args, **kwargs))
    for i in ids if isinstance(ids, (list, tuple)) else [ids]:
        appended_values[i] = plain(self[i].dict())
    return ids


def body_append(self, *args, **kwargs):
    return remember(body_lines, original_body_append(self, *args, **kwargs))


wrapper.MaterialContainer.append = material_append
wrapper.BodyContainer.append = body_append


def watch(name):
    prop = getattr(wrapper.Omega, name)

    def setter(self, value):
        set_lines[name] = script_line()
        prop.fset(self, value)

    setattr(wrapper.Omega, name, property(prop.fget, setter, prop.fdel, prop.__doc__))


for name in ("engines", "dt", "dynDt"):
    watch(name)


def number(x):
    # JSON has no NaN: a value YADE leaves at NaN ("not given") is null.
    x = float(x)
    return x if math.isfinite(x) else None


def plain(value):
    """A YADE value as JSON: numbers, strings, flags, vectors; a MatchMaker with its table; any
    other object by its class and attributes."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        return number(value)
    if isinstance(value, wrapper.MatchMaker):
        return {
            "match_maker": {
                "matches": [[number(x) for x in m] for m in value.matches],
                "algo": value.algo,
                "val": number(value.val),
            }
        }
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "dict") and hasattr(value, "__class__"):
        try:
            return {"object": {"class": value.__class__.__name__, "attributes": plain(value.dict())}}
        except Exception:
            pass
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    try:
        return [number(x) for x in value]
    except Exception:
        return {"object": {"class": value.__class__.__name__, "attributes": {}}}


def same(a, b):
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    try:
        return bool(a == b)
    except Exception:
        return False


def changed(obj):
    """The attributes whose values differ from a fresh instance's: what the script set."""
    try:
        defaults = type(obj)().dict()
    except Exception:
        return sorted(obj.dict())
    return [k for k, v in obj.dict().items() if k not in defaults or not same(v, defaults[k])]


def functor(f, materials):
    """A functor: its class, attributes and each MatchMaker evaluated per pair of materials by
    their ids, as its Ip2 evaluates it (`(*en)(mat1->id, mat2->id)`)."""
    attributes = plain(f.dict())
    per_pair = {}
    for key, value in f.dict().items():
        if isinstance(value, wrapper.MatchMaker):
            table = []
            for i in materials:
                for j in materials:
                    try:
                        table.append([i, j, number(value(i, j))])
                    except Exception:
                        table.append([i, j, None])
            per_pair[key] = table
    return {
        "class": f.__class__.__name__,
        "attributes": attributes,
        "changed": changed(f),
        "per_pair": per_pair,
    }


def engine(e, materials):
    out = {"class": e.__class__.__name__, "attributes": {}, "changed": [], "functors": None}
    if isinstance(e, wrapper.InteractionLoop):
        out["functors"] = {
            "geometry": [functor(f, materials) for f in e.geomDispatcher.functors],
            "physics": [functor(f, materials) for f in e.physDispatcher.functors],
            "laws": [functor(f, materials) for f in e.lawDispatcher.functors],
        }
    else:
        try:
            # A periodic engine's realLast is the wall-clock time it was made at: no set-up.
            attributes = {k: v for k, v in e.dict().items() if k != "realLast"}
            out["attributes"] = plain(attributes)
            out["changed"] = [k for k in changed(e) if k != "realLast"]
        except Exception:
            pass
    return out


def body(b):
    shape = b.shape
    kind = shape.__class__.__name__ if shape is not None else None
    material = b.material
    out = {
        "id": b.id,
        "shape": kind,
        "material": material.id if material is not None else None,
        "mass": number(b.state.mass),
        "dynamic": bool(b.dynamic),
        "blocked": b.state.blockedDOFs,
        "clump": b.isClump or b.isClumpMember,
        "line": body_lines.get(b.id),
        "radius": None,
        "extents": None,
    }
    if kind == "Sphere":
        out["radius"] = number(shape.radius)
        out["vel"] = [number(x) for x in b.state.vel]
    elif kind == "Box":
        out["extents"] = [number(x) for x in shape.extents]
    return out


def dump(stopped):
    O = wrapper.Omega()
    materials = [m.id for m in O.materials]
    engines = list(O.engines)
    data = {
        "version": str(yade.config.version),
        "stopped": stopped,
        "saved": [line for line in saved],
        "dt": number(O.dt),
        "dt_line": set_lines.get("dt"),
        "dyn_dt": bool(O.dynDt),
        "engines_line": set_lines.get("engines"),
        "materials": [
            {
                "id": m.id,
                "class": m.__class__.__name__,
                "attributes": plain(m.dict()),
                "changed": changed(m),
                "appended": appended_values.get(m.id),
                "line": material_lines.get(m.id),
            }
            for m in O.materials
        ],
        "engines": [engine(e, materials) for e in engines],
        "bodies": [body(b) for b in O.bodies if b is not None],
    }
    with open(DUMP + ".part", "w") as out:
        json.dump(data, out, allow_nan=False)
    os.replace(DUMP + ".part", DUMP)


# The names a script run by `yade -x` finds without importing them, as the launcher gives them.
namespace = {"__name__": "__main__", "__file__": SCRIPT, "__builtins__": __builtins__}
exec(
    "import yade\nfrom yade import utils, pack, geom\nfrom yade.utils import *\nfrom yade.pack import *\nfrom math import *\n",
    namespace,
)
sys.argv = [SCRIPT]
yade.runtime.argv = [SCRIPT]
print("MILLIMPACT version=" + str(yade.config.version))
stopped = None
try:
    with open(SCRIPT) as source:
        code = compile(source.read(), SCRIPT, "exec")
    exec(code, namespace)
except StopReading as stop:
    stopped = {"call": stop.call, "line": None}
    for frame in traceback.extract_tb(stop.__traceback__):
        if os.path.abspath(frame.filename) == SCRIPT:
            stopped["line"] = frame.lineno
except SystemExit as leave:
    # `sys.exit()` or `exit(0)` ends the set-up as the end of the script does; another status
    # is the script's own failure.
    if leave.code not in (None, 0):
        line = None
        for frame in traceback.extract_tb(leave.__traceback__):
            if os.path.abspath(frame.filename) == SCRIPT:
                line = frame.lineno
        print("MILLIMPACT raised line=%s SystemExit: %s" % (line, leave.code))
        sys.stdout.flush()
        sys.exit(3)
except BaseException as error:
    line = getattr(error, "lineno", None) if isinstance(error, SyntaxError) else None
    for frame in traceback.extract_tb(error.__traceback__):
        if os.path.abspath(frame.filename) == SCRIPT:
            line = frame.lineno
    message = "".join(traceback.format_exception_only(type(error), error)).strip().replace("\n", " ")
    print("MILLIMPACT raised line=%s %s" % (line, message))
    sys.stdout.flush()
    sys.exit(3)
dump(stopped)
print("MILLIMPACT dumped")
