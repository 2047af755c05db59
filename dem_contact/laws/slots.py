"""Named slots of the parameter row and of the history row (float64 arrays).

Parameter row (one per pair type), read by every kernel:

====================  =====================================================================
slot                  meaning [unit]
====================  =====================================================================
P_ESTAR               effective Young's modulus E* [Pa]
P_GSTAR               effective shear modulus G* [Pa]
P_RSTAR               effective radius R* [m]
P_MSTAR               effective mass m* [kg]
P_MU                  friction coefficient mu [-]
P_PY                  limiting contact pressure p_y [Pa] (thornton)
P_DELTA_Y             yield overlap delta_y [m] (thornton)
P_F_Y                 yield force F_y [N] (thornton)
P_GAMMA               dashpot ratio gamma [-] (hertz_damped, linear)
P_KN                  linear normal stiffness [N/m] (linear)
P_KT                  linear tangential stiffness [N/m] (tangential linear)
P_NSPRING             number of springs of the MDR reference (mdr)
P_DX                  spring spacing of the MDR reference [m] (mdr)
P_MDR_PROFILE         Coulomb-limit profile of the MDR laws: 0 the pressure the normal law implies
                      (Hertz truncated at p_y during Thornton's plastic loading), 1 a Hertz shape scaled
                      to N (the MDR laws)
P_TY_NODES            nodes of the traction-yield table, 0 = off (thornton)
P_TY_DMU              spacing of the table in mu_eff = |T|/N [-] (thornton)
P_TY_TABLE ...        p0(mu_eff)/p0(0) at mu_eff = 0, P_TY_DMU, ... (TY_MAX_NODES slots; thornton)
P_NORMAL_LAW          normal law id + 1 the row was built for (0: not recorded); no kernel reads it,
                      the checked entries refuse a row used with other law ids
P_TANGENTIAL_LAW      tangential law id + 1 the row was built for (0: not recorded)
P_TWIST_LAW           twist law id + 1 the row was built for (0: not recorded; the 3D kernels read it)
P_ROLLING_LAW         rolling law id + 1 the row was built for (0: not recorded; the 3D kernels read it)
P_K_TWIST             twist spring: k_twist [N m/rad] (twist sds); the tangential coefficient k_t the
                      marshall twist is scaled from (8 G* [Pa], or the linear law's k_t [N/m])
P_GAMMA_TWIST         twist dashpot: gamma_twist [N m s/rad] (twist sds); the tangential damping the
                      marshall twist is scaled from (0: the tangential laws have none)
P_MU_TWIST            twist slider: mu_twist [m] (twist sds; the limit is mu_twist N)
P_K_ROLL              rolling spring k_roll [N/m] (rolling sds)
P_GAMMA_ROLL          rolling dashpot gamma_roll [N s/m] (rolling sds)
P_MU_ROLL             rolling slider mu_roll [-] (rolling sds; the limit of the pseudo-force is mu_roll N)
P_G_TWIST             shear modulus of the twist G_c [Pa], 1/G_c = 1/G1 + 1/G2 (twist deresiewicz)
====================  =====================================================================

History row (one per contact), updated in place: a header, then the normal slots, then the
tangential slots. ``H_TANG_EXTRA`` is where laws with a variable-length state (the MDR springs) start.
"""

# parameter row
P_ESTAR = 0
P_GSTAR = 1
P_RSTAR = 2
P_MSTAR = 3
P_MU = 4
P_PY = 5
P_DELTA_Y = 6
P_F_Y = 7
P_GAMMA = 8
P_KN = 9
P_KT = 10
P_NSPRING = 11
P_DX = 12
P_MDR_PROFILE = 13
P_TY_NODES = 14
P_TY_DMU = 15
P_TY_TABLE = 16
TY_MAX_NODES = 16
P_NORMAL_LAW = 32
P_TANGENTIAL_LAW = 33
P_TWIST_LAW = 34
P_ROLLING_LAW = 35
P_K_TWIST = 36
P_GAMMA_TWIST = 37
P_MU_TWIST = 38
P_K_ROLL = 39
P_GAMMA_ROLL = 40
P_MU_ROLL = 41
P_G_TWIST = 42
N_PARAMS = 43

# history row: header
H_N = 0        # normal force after the last step [N] (clamped at >= 0)
H_A = 1        # contact radius after the last step [m]
# normal law slots (thornton)
H_DSTAR = 2    # largest overlap reached, delta* [m]
H_FSTAR = 3    # force at delta*, F* [N]
H_RP = 4       # radius of the unloading curve, R_p [m] (0 until yield)
H_DP = 5       # plastic overlap delta_p [m]
# tangential law slots
H_T = 6        # tangential force T (in the direction of the tangential displacement) [N]
H_TS = 7       # unloading reversal point T* (canonical frame, md) [N]
H_TSS = 8      # reloading reversal point T** (canonical frame, md) [N]
H_REGIME = 9   # md regime: 0 loading, 1 unloading, 2 reloading
H_SIGN = 10    # md loading direction, +1 or -1 (0 before the first move)
H_XI = 11      # tangential spring displacement for total-displacement laws [m]
H_TANG_EXTRA = 12
N_HIST_BASE = 12
