"""Named slots of the history row (one per contact, float64, updated in place): a header, then the normal
slots, then the tangential slots. ``H_TANG_EXTRA`` is where laws with a variable-length state (the MDR springs)
start. ``laws.slots`` gives them with the slots of the parameter row."""

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
