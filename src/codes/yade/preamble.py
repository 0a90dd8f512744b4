import math
import sys
import time

if "yade" not in sys.modules:
    # Run by the Python of YADE's launcher, not by the launcher (src/codes/yade/batch.rs):
    # `yade.runtime` imports IPython only to read its version for the launcher's shell, which
    # a batch never opens, so a stand-in takes its place while YADE loads, and leaves.
    import types

    shell = types.ModuleType("IPython")
    shell.__version__ = "0.0"
    sys.modules["IPython"] = shell
    import yade

    del sys.modules["IPython"]
import yade
from yade import *
from yade import utils
from yade.utils import *
