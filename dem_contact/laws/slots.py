"""Named slots of the parameter row (one per pair type, float64[N_PARAMS], read by every kernel) and of
the history row (``laws.history_slots``), generated from the laws' ``PARAMETERS`` by
``python -m dem_contact.laws.generate``: do not edit (a test fails when it is out of date).

Parameter row:

==================  ======================================================================
slot                meaning [unit] (the laws that read it)
==================  ======================================================================
P_ESTAR             effective Young's modulus E* [Pa] (normal hertz, normal thornton, normal hertz_damped, tangential
                    mdr, tangential mdr_adaptive)
P_GSTAR             effective shear modulus G* [Pa] (tangential md, tangential md_rescale, tangential mindlin_total,
                    tangential mindlin_incremental, tangential mindlin_rescale, tangential ddm, tangential mdr,
                    tangential mdr_adaptive)
P_RSTAR             effective radius R* [m] (normal hertz, normal thornton, normal hertz_damped, normal linear,
                    tangential mdr, tangential mdr_adaptive, twist deresiewicz, rolling sds)
P_MSTAR             effective mass m* [kg] (normal hertz_damped, normal linear)
P_MU                friction coefficient mu [-] (tangential md, tangential md_rescale, tangential mindlin_total,
                    tangential mindlin_incremental, tangential mindlin_rescale, tangential linear, tangential ddm,
                    tangential mdr, tangential mdr_adaptive, twist marshall, twist deresiewicz)
P_NORMAL_LAW        normal law id + 1 the row was built for (0: not recorded); no kernel reads it, the checked entries
                    refuse a row used with other law ids
P_TANGENTIAL_LAW    tangential law id + 1 the row was built for (0: not recorded)
P_TWIST_LAW         twist law id + 1 the row was built for (0: not recorded; the 3D kernels read it)
P_ROLLING_LAW       rolling law id + 1 the row was built for (0: not recorded; the 3D kernels read it)
P_PY                limiting contact pressure p_y (0: none) [Pa] (normal thornton, tangential mdr, tangential
                    mdr_adaptive)
P_DELTA_Y           yield overlap delta_y [m] (normal thornton)
P_F_Y               yield force F_y [N] (normal thornton)
P_TY_NODES          nodes of the traction-yield table, 0 = off (normal thornton)
P_TY_DMU            spacing of the traction-yield table in mu_eff = |T|/N [-] (normal thornton)
P_TY_TABLE          p0(mu_eff)/p0(0) at mu_eff = 0, P_TY_DMU, ... (16 slots) (normal thornton)
P_GAMMA             dashpot ratio gamma [-] (normal hertz_damped, normal linear)
P_KN                linear normal stiffness k_n [N/m] (normal linear, tangential linear)
P_KT                linear tangential stiffness k_t [N/m] (normal linear, tangential linear)
P_NSPRING           number of cells (springs) of the MDR laws (tangential mdr, tangential mdr_adaptive)
P_DX                cell width of the fixed MDR grid [m] (tangential mdr, tangential mdr_adaptive)
P_MDR_PROFILE       Coulomb-limit profile of the MDR laws: 0 the pressure the normal law implies (Hertz truncated at
                    p_y during Thornton's plastic loading), 1 a Hertz shape scaled to N (tangential mdr, tangential
                    mdr_adaptive)
P_K_TWIST           twist spring k_twist (marshall: the tangential coefficient k_t it is scaled from) [N m/rad] (twist
                    marshall, twist sds)
P_GAMMA_TWIST       twist dashpot gamma_twist (marshall: the tangential damping it is scaled from) [N m s/rad] (twist
                    marshall, twist sds)
P_MU_TWIST          twist slider mu_twist (the limit is mu_twist N) [m] (twist sds)
P_G_TWIST           shear modulus of the twist G_c, 1/G_c = 1/G1 + 1/G2 [Pa] (twist deresiewicz)
P_K_ROLL            rolling spring k_roll [N/m] (rolling sds)
P_GAMMA_ROLL        rolling dashpot gamma_roll [N s/m] (rolling sds)
P_MU_ROLL           rolling slider mu_roll (the limit of the pseudo-force is mu_roll N) [-] (rolling sds)
==================  ======================================================================
"""
import sys as _sys

from .history_slots import *  # noqa: F401,F403  (the history row)

P_ESTAR = 0
P_GSTAR = 1
P_RSTAR = 2
P_MSTAR = 3
P_MU = 4
P_NORMAL_LAW = 5
P_TANGENTIAL_LAW = 6
P_TWIST_LAW = 7
P_ROLLING_LAW = 8
P_PY = 9
P_DELTA_Y = 10
P_F_Y = 11
P_TY_NODES = 12
P_TY_DMU = 13
P_TY_TABLE = 14
P_TY_TABLE_SIZE = 16
P_GAMMA = 30
P_KN = 31
P_KT = 32
P_NSPRING = 33
P_DX = 34
P_MDR_PROFILE = 35
P_K_TWIST = 36
P_GAMMA_TWIST = 37
P_MU_TWIST = 38
P_G_TWIST = 39
P_K_ROLL = 40
P_GAMMA_ROLL = 41
P_MU_ROLL = 42
N_PARAMS = 43


def __getattr__(name):
    if name.startswith("P_") and "dem_contact.laws.generate" in getattr(_sys, "orig_argv", ()):
        return -1      # a slot a law declares, being numbered now (laws.generate)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}" + (
        ": a slot a law's PARAMETERS declare is numbered by `python -m dem_contact.laws.generate`"
        if name.startswith("P_") else ""))
