/* ----------------------------------------------------------------------
   millimpact: the normal contact law of "Interaction of grinding bodies"
   (Shevchenko, Tytov, Samodryha) as a LIGGGHTS-PUBLIC 3.8.0 normal model.

   The dissipative force is eta times the gradient of the elastic contact
   energy W = C y^(n+1)/(n+1), always opposed to the motion:

       F = C y^n (1 + eta sign(dy/dt))        (y: overlap, compression > 0)

   so loading runs on the stiffness C (1 + eta) and unloading on C (1 - eta),
   both through the origin. The coefficient of restitution of one impact is
   sqrt((1 - eta)/(1 + eta)) for every n, mass, stiffness and speed.

   Two styles, both selected with "model ..." in pair_style gran and
   fix wall/gran:

     model paper          n = 1.5, C = (4/3) E* sqrt(R*) computed exactly as
                          LIGGGHTS's model hertz computes its stiffness
                          (E* from youngsModulus/poissonsRatio per type,
                          R* = R at a wall, R1 R2/(R1 + R2) between spheres)
     model paper/linear   n = 1, C = kn per type pair (as hooke/stiffness)

   eta is a per-type-pair property:

     fix lossCoefficient all property/global lossCoefficient peratomtypepair N ...

   with 0 <= eta < 1 for every pair; anything else stops the run with an
   error naming lossCoefficient.

   Conventions:
   - sign(dy/dt) is taken from the normal relative velocity LIGGGHTS hands
     the model (sidata.vn, negative while the surfaces approach), resolved to
     one step: within the velocity change one step's force jump makes,
     |vn| < 2 eta C y^n dt / meff (meff: the pair's effective mass, the
     sphere's at a wall), the sign is replaced by vn over that band, so a
     contact at rest carries its load on the elastic force C y^n instead of
     alternating between the branches (branchFactor below says why).
   - The force is never attractive: C y^n (1 - eta) >= 0 while y >= 0. It goes
     to zero continuously as the overlap closes, so the contact ends without
     a force jump and no clamp (limitForce) is needed. The model keeps no
     contact history.
   - Tangential: the tangential models read sidata.kt and sidata.gammat.
     model paper gives kt = 8 G* sqrt(R* y), as model hertz; model
     paper/linear gives kt from the per-type-pair property kt, as
     hooke/stiffness. gammat is 0 for both (the paper defines no tangential
     damping), so "tangential no_history" adds no force and
     "tangential history" is a Coulomb-limited spring without a dashpot.

   To build it in, see README.md next to this file. Written for the
   millimpact project; compiled into LIGGGHTS, it is used under LIGGGHTS's
   licence (GPL v2 or later).
------------------------------------------------------------------------- */

#ifdef NORMAL_MODEL
NORMAL_MODEL(PAPER,paper,40)
NORMAL_MODEL(PAPER_LINEAR,paper/linear,41)
#else
#ifndef NORMAL_MODEL_PAPER_H_
#define NORMAL_MODEL_PAPER_H_

#include <cmath>
#include <cstdio>
#include "contact_models.h"
#include "normal_model_base.h"
#include "global_properties.h"
#include "fix_property_global.h"
#include "force.h"
#include "update.h"
#include "error.h"

namespace LIGGGHTS {
namespace ContactModels {

namespace PaperLaw {

  // The per-type-pair loss coefficient eta, checked: 0 <= eta < 1.
  // One function for both styles, so a pair style and a wall that use the two
  // styles register the same creator for the same property name.
  inline MatrixProperty * createLossCoefficient(PropertyRegistry & registry, const char * caller, bool)
  {
    LAMMPS * lmp = registry.getLAMMPS();
    const int max_type = registry.max_type();

    MatrixProperty * matrix = new MatrixProperty(max_type+1, max_type+1);
    FixPropertyGlobal * eta_fix = registry.getGlobalProperty("lossCoefficient", "property/global", "peratomtypepair", max_type, max_type, caller);

    for (int i = 1; i < max_type+1; i++)
    {
      for (int j = 1; j < max_type+1; j++)
      {
        const double eta = eta_fix->compute_array(i-1, j-1);
        // written so that NaN fails too
        if (!(eta >= 0.0 && eta < 1.0))
        {
          char msg[256];
          snprintf(msg, sizeof(msg),
                   "%s: 0 <= lossCoefficient < 1 required (eta = %g for atom types %d %d; "
                   "eta >= 1 never separates the bodies, eta < 0 creates energy)",
                   caller, eta, i, j);
          lmp->error->all(FLERR, msg);
        }
        matrix->data[i][j] = eta;
      }
    }
    return matrix;
  }

  // 1 + eta s, with s the sign of dy/dt = -vn (vn < 0 while approaching) as one step of
  // length dt can resolve it. The continuous law is set-valued at dy/dt = 0: a contact at rest
  // may carry any force between C y^n (1 - eta) and C y^n (1 + eta). One step's force jump
  // between the branches, 2 eta C y^n, changes the relative normal velocity by
  // band = 2 eta C y^n dt / meff; a plain sign would flip the branch every step in a resting
  // contact (its half-step velocity alternates by that much) and the force with it. So s
  // follows the sign outside the band and is linear inside it, dy/dt / band: the dissipative
  // force there is meff (dy/dt) / (2 dt), which halves a lone contact's relative normal
  // velocity per step (a body pressed along one line by three such contacts still comes to
  // rest), so a resting contact comes to rest and carries its load on the elastic force.
  inline double branchFactor(const double eta, const double Fn_elastic, const double vn, const double meff, const double dt)
  {
    const double rate = -vn;
    const double band = 2.0 * eta * Fn_elastic * dt / meff;
    if (rate >= band) return 1.0 + eta;   // loading (also eta = 0 or no force: band = 0)
    if (rate <= -band) return 1.0 - eta;  // unloading
    return 1.0 + eta * (rate / band);     // within one step of rest
  }

  // Adds the normal force Fn (> 0 repulsive) along en, as the stock normal models do
  // for spheres (no torque from the normal force).
  inline void applyNormalForce(SurfacesIntersectData & sidata, ForceData & i_forces, ForceData & j_forces, const double Fn)
  {
    if (sidata.is_wall)
    {
      const double Fn_wall = Fn * sidata.area_ratio;
      i_forces.delta_F[0] += Fn_wall * sidata.en[0];
      i_forces.delta_F[1] += Fn_wall * sidata.en[1];
      i_forces.delta_F[2] += Fn_wall * sidata.en[2];
    }
    else
    {
      i_forces.delta_F[0] += Fn * sidata.en[0];
      i_forces.delta_F[1] += Fn * sidata.en[1];
      i_forces.delta_F[2] += Fn * sidata.en[2];
      j_forces.delta_F[0] -= Fn * sidata.en[0];
      j_forces.delta_F[1] -= Fn * sidata.en[1];
      j_forces.delta_F[2] -= Fn * sidata.en[2];
    }
  }

} // namespace PaperLaw

  // model paper: Hertz, n = 1.5
  template<>
  class NormalModel<PAPER> : public NormalModelBase
  {
  public:
    NormalModel(LAMMPS * lmp, IContactHistorySetup * hsetup, class ContactModelBase * c) :
      NormalModelBase(lmp, hsetup, c),
      Yeff(NULL),
      Geff(NULL),
      eta(NULL)
    {
    }

    void registerSettings(Settings &) {}

    inline void postSettings(IContactHistorySetup *, ContactModelBase *) {}

    void connectToProperties(PropertyRegistry & registry)
    {
      registry.registerProperty("Yeff", &MODEL_PARAMS::createYeff);
      registry.registerProperty("Geff", &MODEL_PARAMS::createGeff);
      registry.registerProperty("lossCoefficient", &PaperLaw::createLossCoefficient);

      registry.connect("Yeff", Yeff, "model paper");
      registry.connect("Geff", Geff, "model paper");
      registry.connect("lossCoefficient", eta, "model paper");
    }

    inline double stressStrainExponent()
    {
      return 1.5;
    }

    inline void surfacesIntersect(SurfacesIntersectData & sidata, ForceData & i_forces, ForceData & j_forces)
    {
      if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_NORMAL_MODEL;
      if (sidata.is_non_spherical)
        error->one(FLERR, "the paper's normal models are written for spheres only");

      const int itype = sidata.itype;
      const int jtype = sidata.jtype;
      const double reff = sidata.is_wall ? sidata.radi : (sidata.radi*sidata.radj/(sidata.radi+sidata.radj));

      const double deltan = sidata.deltan;
      if (deltan < 0.0)
        error->one(FLERR, "model paper: negative overlap");

      // the stiffness exactly as model hertz forms it: F = kn y, kn = (4/3) E* sqrt(R* y)
      const double sqrtval = sqrt(reff*deltan);
      const double kn = 4./3.*Yeff[itype][jtype]*sqrtval / force->nktv2p;
      const double kt = 8.*Geff[itype][jtype]*sqrtval / force->nktv2p;

      const double Fn_elastic = kn*deltan;
      const double Fn = Fn_elastic * PaperLaw::branchFactor(eta[itype][jtype], Fn_elastic, sidata.vn, sidata.meff, update->dt);

      sidata.Fn = Fn;
      sidata.kn = kn;
      sidata.kt = kt;
      sidata.gamman = 0.0;
      sidata.gammat = 0.0;

      PaperLaw::applyNormalForce(sidata, i_forces, j_forces, Fn);
    }

    void surfacesClose(SurfacesCloseData & scdata, ForceData &, ForceData &)
    {
      if (scdata.contact_flags) *scdata.contact_flags |= CONTACT_NORMAL_MODEL;
    }

    void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
    void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

  protected:
    double ** Yeff;
    double ** Geff;
    double ** eta;
  };

  // model paper/linear: a linear spring, n = 1, stiffness kn per type pair
  template<>
  class NormalModel<PAPER_LINEAR> : public NormalModelBase
  {
  public:
    NormalModel(LAMMPS * lmp, IContactHistorySetup * hsetup, class ContactModelBase * c) :
      NormalModelBase(lmp, hsetup, c),
      k_n(NULL),
      k_t(NULL),
      eta(NULL)
    {
    }

    void registerSettings(Settings &) {}

    inline void postSettings(IContactHistorySetup *, ContactModelBase *) {}

    void connectToProperties(PropertyRegistry & registry)
    {
      registry.registerProperty("k_n", &MODEL_PARAMS::createKn);
      registry.registerProperty("k_t", &MODEL_PARAMS::createKt);
      registry.registerProperty("lossCoefficient", &PaperLaw::createLossCoefficient);

      registry.connect("k_n", k_n, "model paper/linear");
      registry.connect("k_t", k_t, "model paper/linear");
      registry.connect("lossCoefficient", eta, "model paper/linear");

      // a stiffness given per type pair does not scale with coarse-graining
      if (force->cg_active())
        error->cg(FLERR, "model paper/linear");
    }

    inline double stressStrainExponent()
    {
      return 1.0;
    }

    inline void surfacesIntersect(SurfacesIntersectData & sidata, ForceData & i_forces, ForceData & j_forces)
    {
      if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_NORMAL_MODEL;
      if (sidata.is_non_spherical)
        error->one(FLERR, "the paper's normal models are written for spheres only");

      const int itype = sidata.itype;
      const int jtype = sidata.jtype;
      const double kn = k_n[itype][jtype] / force->nktv2p;
      const double kt = k_t[itype][jtype] / force->nktv2p;

      const double Fn_elastic = kn*sidata.deltan;
      const double Fn = Fn_elastic * PaperLaw::branchFactor(eta[itype][jtype], Fn_elastic, sidata.vn, sidata.meff, update->dt);

      sidata.Fn = Fn;
      sidata.kn = kn;
      sidata.kt = kt;
      sidata.gamman = 0.0;
      sidata.gammat = 0.0;

      PaperLaw::applyNormalForce(sidata, i_forces, j_forces, Fn);
    }

    void surfacesClose(SurfacesCloseData & scdata, ForceData &, ForceData &)
    {
      if (scdata.contact_flags) *scdata.contact_flags |= CONTACT_NORMAL_MODEL;
    }

    void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
    void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

  protected:
    double ** k_n;
    double ** k_t;
    double ** eta;
  };

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // NORMAL_MODEL_PAPER_H_
#endif // NORMAL_MODEL
