"""Sweeps: many independent impacts of one scene in a parallel kernel, and the direct critical angle.

``sweep_angles`` varies the impact angle at fixed normal speed (the protocol of Wu, Thornton & Li 2009),
``sweep_speed`` at fixed total speed (Kharaz et al. 2001; Chung & Ooi test 4), ``sweep_theta`` aims at
given values of Theta, ``sweep`` takes any list of (vn, vt, spin). ``scene_with`` / ``sweep_scenes``
build parameter studies (one Scene per value of mu or of a Poisson ratio). ``critical_angle`` finds the
smallest angle at which the contact slides at every step (bisection on repeated impacts): the direct
simulation estimate of Theta_c (Wu, Thornton & Li 2009, section 4).

Each impact has its own history row and output row, so the cost is linear in the number of impacts and
the results equal single ``impact`` calls exactly.
"""
from __future__ import annotations

import dataclasses
import math
import re
import sys
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numba import njit, prange, types
from numba.core import event as numba_event

from ..errors import InputError, NumericalError
from .impact import (MAX_CONTACT_TIMES, SCALE_RANGE, SCHEMES, body_row, build_result, check_incident,
                     check_law_grid, check_law_reach, check_scales, derived_arrays, impact, speed_range, time_step)
from .integrator import INTEGRATOR, N_OUT, N_SERIES, borrowed, integrator_for
from ..materials import Material, Sphere, Wall, check_finite
from ..laws.model import Scene
from ..laws.slots import H_A

#: Work budget of one sweep: total steps per contact time summed over its impacts (about 1e8 steps per
#: second and core with the default law).
MAX_SWEEP_STEPS = 1e10
#: Impacts per progress-bar update are chosen so that the bar advances about this many times.
PROGRESS_UPDATES = 20


_SWEEP = []


class compile_notice(numba_event.Listener):
    """Context manager: when ``on``, say on stderr that kernels are being compiled when numba compiles one
    inside the block (its "numba:compile" event, which a kernel loaded from numba's cache does not raise),
    and at the end how long the compilations took. Nothing is printed when the kernels come from the cache
    or are already loaded, so the block may hold the computation too."""

    def __init__(self, on: bool = True):
        self.on = on
        self.compiled = False
        self.depth = 0
        self.seconds = 0.0

    def on_start(self, event):
        if not self.compiled:
            self.compiled = True
            print("compiling kernels (stored in numba's cache for later runs) ...", file=sys.stderr, flush=True)
        if self.depth == 0:
            self.t0 = time.perf_counter()
        self.depth += 1

    def on_end(self, event):
        self.depth -= 1
        if self.depth == 0:
            self.seconds += time.perf_counter() - self.t0

    def __enter__(self):
        if self.on:
            numba_event.register("numba:compile", self)
        return self

    def __exit__(self, *exc):
        if self.on:
            numba_event.unregister("numba:compile", self)
            if self.compiled and exc[0] is None:
                print(f"kernels compiled in {self.seconds:.0f} s", file=sys.stderr, flush=True)
        return False


def sweep_kernel():
    """The sweep kernel (compiled on first use): ``kernel(integrate, p, hist, body, vn, vt, w1, w2, dt,
    max_steps, locate, out)`` integrates independent impacts in parallel (prange over
    impacts, numba.get_num_threads() threads) with ``integrate``, the integrator of the scene's laws
    (``integrator.integrator_for``, a first-class function: one kernel serves every law pair).

    p: parameter row, body: ``impact.body_row`` (shared, read only); hist: float64[n, n_hist], one row per
    impact (written);
    vn, vt, w1, w2, dt: float64[n] incident normal speed [m/s], tangential velocity [m/s], spins [rad/s],
    time step [s]; max_steps: int64[n]; out: float64[n, N_OUT] (written, slots ``integrator.O_*``).
    """
    if not _SWEEP:
        _SWEEP.append(_sweep_kernel())
    return _SWEEP[0]


def _sweep_kernel():
    vec = types.float64[::1]
    mat = types.float64[:, ::1]
    sig = types.void(types.FunctionType(INTEGRATOR), vec, mat, vec, vec, vec, vec, vec, vec, types.int64[::1],
                     types.boolean, mat)

    @njit(sig, parallel=True, cache=True)
    def kernel(integrate, p, hist, body, vn, vt, w1, w2, dt, max_steps, locate, out):
        # uncounted views: the threads do not share atomic reference counts at every impact
        series = np.zeros((0, N_SERIES))
        p_, body_, hist_, out_, series_ = borrowed(p), borrowed(body), borrowed(hist), borrowed(out), borrowed(series)
        for i in prange(vn.shape[0]):
            integrate(p_, hist_[i], body_, vn[i], vt[i], w1[i], w2[i], dt[i], max_steps[i], locate, out_[i], series_)
    return kernel


class _Points(Sequence):
    """The impacts of a sweep as ImpactResults, each built from its output row when first asked for."""

    def __init__(self, sweep_result):
        self._res = sweep_result
        self._built = {}

    def __len__(self):
        return self._res._out.shape[0]

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        n = len(self)
        k = int(i)
        if k < 0:
            k += n
        if not 0 <= k < n:
            raise IndexError(f"impact {i} of a sweep of {n}")
        r = self._built.get(k)
        if r is None:
            r = self._res._point(k)
            self._built[k] = r
        return r


class SweepResult:
    """Impacts of one sweep: the main quantities as arrays, ``points`` (one ImpactResult per impact, built
    when read), ``model`` and ``settings``.

    theta_deg: impact angle of the centre velocity from the normal [deg]; Theta, Psi_r, Omega_r: the
    dimensionless groups of Wu, Thornton & Li 2009, section 2; f_over_mu: impulse ratio over mu; e_t (NaN at 0 deg),
    e_n; persistent_sliding: the contact slid at every step; energy_created, energy_gained: the flags of
    ``ImpactResult``.
    """

    def __init__(self, scene, out, vn, vt, spin, dts, spcs, scheme, model, settings, derived):
        self._scene, self._out, self._vn, self._vt, self._spin = scene, out, vn, vt, spin
        self._dts, self._spcs, self._scheme = dts, spcs, scheme
        self._warned = derived["warned"]
        self.model = model
        self.settings = settings
        for name in ("theta_deg", "Theta", "f_over_mu", "e_t", "e_n", "Psi_r", "Omega_r", "Omega_i",
                     "persistent_sliding", "energy_created", "energy_gained"):
            setattr(self, name, derived[name])
        self.points = _Points(self)

    def _point(self, i):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # recorded in ImpactResult.warnings
            return build_result(self._scene, self._out[i], float(self._vn[i]), float(self._vt[i]),
                                float(self._spin[i]), 0.0, float(self._dts[i]), float(self._spcs[i]), self._scheme,
                                model=self.model)

    def __len__(self):
        return self._out.shape[0]

    @property
    def warnings(self) -> list:
        """The warnings of the impacts, one per kind (the same text but for its numbers), each with the
        number of impacts that raised it; a number that differs between them is given as its range."""
        return merge_warnings([self.points[i].warnings for i in np.flatnonzero(self._warned)], len(self))

    def to_dicts(self) -> list:
        """One JSON-ready dict per impact (the ImpactResult keys)."""
        return [r.to_dict() for r in self.points]


#: A number in a warning's text (not part of a name such as thornton2001 or R*).
_NUMBER = re.compile(r"(?<![\w.*])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?!\w)")


def merge_warnings(per_impact, n_impacts: int) -> list:
    """One line per kind of warning over the impacts' warning lists ``per_impact``: a kind is a text with its
    numbers left out; a number that is the same in every impact is kept, one that differs is given as
    "MIN to MAX"; each line ends with the number of impacts that raised it, of ``n_impacts``."""
    kinds = {}
    for msgs in per_impact:
        for w in msgs:
            key = _NUMBER.sub("#", w)
            kinds.setdefault(key, []).append(_NUMBER.findall(w))
    lines = []
    for key, numbers in kinds.items():
        parts = key.split("#")
        text = parts[0]
        for k, part in enumerate(parts[1:]):
            column = [nums[k] for nums in numbers]
            values = [float(x) for x in column]
            lo, hi = column[values.index(min(values))], column[values.index(max(values))]
            text += (lo if lo == hi or min(values) == max(values) else f"{lo} to {hi}") + part
        lines.append(f"{text} ({len(numbers)} of {n_impacts} impacts)")
    return lines


def _check_inputs(scene, vn, vt, spin):
    """check_incident and check_scales on arrays: the scalar checks raise for the first bad impact."""
    v_lo, v_hi = speed_range(scene)
    ok = np.isfinite(vn) & np.isfinite(vt) & np.isfinite(spin) & (vn > 0.0) & (vn >= v_lo) & (vn <= v_hi)
    ok &= np.abs(vt) <= math.sqrt(2.0 * SCALE_RANGE[1] / scene.pair.m_star)
    if isinstance(scene.sphere, Sphere):
        ok &= np.abs(spin) <= math.sqrt(2.0 * SCALE_RANGE[1] / scene.sphere.inertia)
    bad = np.flatnonzero(~ok)
    if bad.size:
        i = bad[0]
        check_incident(vn[i], vt[i], spin[i])
        check_scales(scene, vn[i], vt[i], spin[i])
        raise InputError(f"impact {i}: vn = {vn[i]:g}, vt = {vt[i]:g}, spin = {spin[i]:g} out of range")


def sweep(scene: Scene, vn, vt, spin=0.0, *, steps_per_contact: float | None = None, scheme: str = "located",
          progress: bool = False) -> SweepResult:
    """Simulate independent impacts given by arrays (or scalars, broadcast) vn > 0 [m/s], vt [m/s] and
    spin [rad/s]. Each impact gets ``steps_per_contact`` steps per elastic contact time at its own vn.
    Raises NumericalError naming the first impact that failed."""
    if not isinstance(scene, Scene):
        raise InputError("scene must be a Scene")
    if scheme not in SCHEMES:
        raise InputError(f"scheme {scheme!r} is unknown; choose one of: {', '.join(SCHEMES)}")
    vn, vt, spin = (np.atleast_1d(np.asarray(x, dtype=float)) for x in (vn, vt, spin))
    try:
        vn, vt, spin = (np.ascontiguousarray(x) for x in np.broadcast_arrays(vn, vt, spin))
    except ValueError:
        raise InputError(f"vn, vt and spin must have the same length or be scalars "
                         f"(got {vn.size}, {vt.size}, {spin.size})") from None
    if vn.ndim != 1 or vn.size == 0:
        raise InputError("vn, vt and spin must be one-dimensional with at least one impact")
    n = vn.size
    _check_inputs(scene, vn, vt, spin)
    # one time step per distinct normal speed (a sweep at fixed vn computes it once)
    speeds, where = np.unique(vn, return_inverse=True)
    steps = [time_step(scene, v, steps_per_contact, None) for v in speeds]
    dts = np.array([d for d, _ in steps])[where]
    spcs = np.array([c for _, c in steps])[where]
    work = float(np.sum(spcs))
    if work > MAX_SWEEP_STEPS:
        raise InputError(f"the sweep asks for {work:.3g} steps ({n} impacts x {work / n:.3g} steps per contact); "
                         f"the limit is {MAX_SWEEP_STEPS:.3g}: use fewer impacts or fewer steps per contact")
    check_law_reach(scene, float(vn.max()))
    max_steps = np.ceil(MAX_CONTACT_TIMES * spcs).astype(np.int64) + 10
    out = np.zeros((n, N_OUT))
    hist = np.zeros((n, scene.history_size))
    w2 = np.zeros(n)
    locate = scheme == "located"
    chunk = n if not progress else max(1, -(-n // PROGRESS_UPDATES))
    with compile_notice(progress):
        kernel = sweep_kernel()
        args = (integrator_for(scene.normal_id, scene.tangential_id), scene.params)
    body = body_row(scene)
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=n, unit="impact", desc=f"sweep {scene.tangential}", leave=False)
    try:
        for s in range(0, n, chunk):
            e = min(n, s + chunk)
            try:
                kernel(*args, hist[s:e], body, vn[s:e], vt[s:e], spin[s:e], w2[s:e], dts[s:e], max_steps[s:e],
                       locate, out[s:e])
            except Exception as err:     # a failure inside the compiled code (parallel region, law): no result
                raise NumericalError(f"the {scene.normal}/{scene.tangential} kernels failed in impacts {s} to "
                                     f"{e - 1} ({type(err).__name__}: {err})") from None
            if bar is not None:
                bar.update(e - s)
    finally:
        if bar is not None:
            bar.close()
    derived = derived_arrays(scene, out, vn, vt, spin, 0.0, spcs)
    failed = derived["failed"]
    reach = scene.tangential_law.max_radius(scene)
    if reach is not None:
        failed = failed | (hist[:, H_A] > reach)
    bad = np.flatnonzero(failed)
    if bad.size:
        i = bad[0]
        try:
            check_law_grid(scene, hist[i], vn[i])
            build_result(scene, out[i], vn[i], vt[i], spin[i], 0.0, dts[i], spcs[i], scheme)
            raise NumericalError("non-finite result")
        except NumericalError as err:
            raise NumericalError(f"impact {i} (vn = {vn[i]:g} m/s, vt = {vt[i]:g} m/s, spin = "
                                 f"{spin[i]:g} rad/s) failed: {err}") from None
    settings = {"scheme": scheme, "steps_per_contact": float(spcs[0]) if np.all(spcs == spcs[0]) else None,
                "n_impacts": n}
    return SweepResult(scene, out, vn, vt, spin, dts, spcs, scheme, scene.describe(), settings, derived)


def _angles(angles_deg) -> np.ndarray:
    a = np.atleast_1d(np.asarray(angles_deg, dtype=float))
    if a.ndim != 1 or a.size == 0:
        raise InputError("angles_deg must be a non-empty list of angles [deg]")
    bad = np.flatnonzero(~((a > -90.0) & (a < 90.0)))
    if bad.size:
        check_finite("impact angle (deg)", a[bad[0]], lo=-90.0, hi=90.0, lo_open=True, hi_open=True)
    return a


def sweep_angles(scene: Scene, angles_deg, vn: float = 5.0, spin: float = 0.0, *,
                 steps_per_contact: float | None = None, scheme: str = "located", progress: bool = False) -> SweepResult:
    """Impacts at angles ``angles_deg`` from the normal at FIXED normal speed vn [m/s]:
    vt = vn tan(angle) (the protocol of Wu et al. 2009)."""
    a = _angles(angles_deg)
    vn = check_finite("vn (normal impact speed towards the wall, m/s)", vn, lo=0.0)
    res = sweep(scene, vn, vn * np.tan(np.radians(a)), spin, steps_per_contact=steps_per_contact,
                scheme=scheme, progress=progress)
    res.settings.update(protocol="fixed normal speed", vn=vn, spin=spin)
    return res


def sweep_speed(scene: Scene, angles_deg, speed: float = 5.0, spin: float = 0.0, *,
                steps_per_contact: float | None = None, scheme: str = "located", progress: bool = False) -> SweepResult:
    """Impacts at angles ``angles_deg`` at FIXED total speed [m/s]: vn = speed cos(angle), vt = speed
    sin(angle) (Kharaz et al. 2001; Chung & Ooi test 4). Angles must be below 90 deg."""
    a = _angles(angles_deg)
    speed = check_finite("speed (total impact speed, m/s)", speed, lo=0.0)
    r = np.radians(a)
    res = sweep(scene, speed * np.cos(r), speed * np.sin(r), spin, steps_per_contact=steps_per_contact,
                scheme=scheme, progress=progress)
    res.settings.update(protocol="fixed total speed", speed=speed, spin=spin)
    return res


def sweep_theta(scene: Scene, Theta, vn: float = 5.0, *, steps_per_contact: float | None = None,
                scheme: str = "located", progress: bool = False) -> SweepResult:
    """Impacts aimed at the dimensionless incidence Theta = 2 tan(theta_i) / ((1 + e_n) mu), taking
    e_n = 1: vt = Theta mu vn. The Theta reported is computed from the simulated e_n. Needs mu > 0."""
    if scene.mu <= 0:
        raise InputError("sweep_theta needs mu > 0")
    T = np.atleast_1d(np.asarray(Theta, dtype=float))
    bad = np.flatnonzero(~((T >= 0.0) & np.isfinite(T)))
    if bad.size:
        check_finite("Theta (dimensionless incidence)", T[bad[0]], lo=0.0, lo_open=False)
    vn = check_finite("vn (normal impact speed towards the wall, m/s)", vn, lo=0.0)
    res = sweep(scene, vn, T * scene.mu * vn, 0.0, steps_per_contact=steps_per_contact, scheme=scheme,
                progress=progress)
    res.settings.update(protocol="fixed normal speed, aimed at Theta", vn=vn, spin=0.0)
    return res


def scene_with(scene: Scene, *, mu: float | None = None, nu: float | None = None, body: str = "elastic",
               **kwargs) -> Scene:
    """A copy of ``scene`` with another friction coefficient ``mu`` and/or Poisson ratio ``nu``.

    body: which material takes ``nu``: "sphere", "wall" (body 2), "both", or "elastic" (every non-rigid
    body; the default). Other keyword arguments (any argument of ``Scene``: normal, tangential, e_n, v_ref,
    model, mdr_profile, traction_yield, mdr_springs, ...) replace the scene's; every other setting is kept
    (``Scene.replace``; another tangential law: ``Scene.with_tangential``). A normal or tangential law other
    than those of the scene's named ``model`` leaves the model: its laws stay where not given."""
    if body not in ("sphere", "wall", "both", "elastic"):
        raise InputError(f"body {body!r} is unknown; choose one of: sphere, wall, both, elastic")
    changes = dict(kwargs)
    if mu is not None:
        changes["mu"] = mu
    if nu is not None:
        sphere, body2 = scene.sphere, scene.body2

        def swap(mat: Material, wanted: bool) -> Material:
            if not wanted or mat.is_rigid:
                return mat
            return dataclasses.replace(mat, nu=nu)

        m1 = swap(sphere.material, body in ("sphere", "both", "elastic"))
        m2 = swap(body2.material, body in ("wall", "both", "elastic"))
        if m1 is sphere.material and m2 is body2.material:
            raise InputError(f"nu cannot be set on body {body!r}: it is rigid")
        changes["sphere"] = Sphere(sphere.radius, m1)
        changes["body2"] = Sphere(body2.radius, m2) if isinstance(body2, Sphere) else Wall(m2)
    if scene.model is not None and "model" not in changes and any(
            changes.get(k, getattr(scene, k)) != getattr(scene, k) for k in ("normal", "tangential")):
        changes = {"model": None, "normal": scene.normal, **changes}
    elif scene.model is not None and "model" not in changes:
        changes.pop("normal", None)         # the model's own laws: the model stays
        changes.pop("tangential", None)
    return scene.with_tangential(changes.pop("tangential", scene.tangential), **changes)


def sweep_scenes(scenes: dict, angles_deg=None, vn: float = 5.0, *, Theta=None, **kwargs) -> dict:
    """Parameter study: the same sweep for each Scene of ``scenes`` (label -> Scene). Give either
    ``angles_deg`` (fixed normal speed) or ``Theta`` (see ``sweep_theta``). Returns label -> SweepResult."""
    if (angles_deg is None) == (Theta is None):
        raise InputError("give either angles_deg or Theta")
    if Theta is not None:
        return {k: sweep_theta(s, Theta, vn, **kwargs) for k, s in scenes.items()}
    return {k: sweep_angles(s, angles_deg, vn, **kwargs) for k, s in scenes.items()}


@dataclass
class CriticalAngle:
    """Smallest impact angle (at fixed vn, no spin) at which the contact slides at every step, bracketed
    to ``tol_deg``; Theta and e_n are those of the first sliding impact (at angle_deg)."""

    angle_deg: float
    Theta: float
    bracket_deg: tuple
    impacts: int
    e_n: float


def critical_angle(scene: Scene, vn: float = 5.0, *, steps_per_contact: float | None = None,
                   scheme: str = "located", tol_deg: float = 1e-6, lo_deg: float = 0.0,
                   hi_deg: float = 89.5) -> CriticalAngle:
    """Direct simulation estimate of the critical angle (Wu, Thornton & Li 2009, section 4): bisection in the impact
    angle on repeated impacts, between a non-sliding ``lo_deg`` and a persistently sliding ``hi_deg``.
    Raises NumericalError when the bracket does not hold (no sliding even at hi_deg)."""
    vn = check_finite("vn (normal impact speed towards the wall, m/s)", vn, lo=0.0)
    tol_deg = check_finite("tol_deg", tol_deg, lo=0.0)
    if scene.mu <= 0:
        raise InputError("critical_angle needs mu > 0")
    count = [0]

    def run(angle):
        count[0] += 1
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return impact(scene, vn, vn * math.tan(math.radians(angle)), steps_per_contact=steps_per_contact,
                          scheme=scheme)

    lo, hi = float(lo_deg), float(hi_deg)
    if run(lo).persistent_sliding:
        raise NumericalError(f"the contact already slides at every step at {lo:g} deg")
    r_hi = run(hi)
    if not r_hi.persistent_sliding:
        raise NumericalError(f"no persistent sliding up to {hi:g} deg")
    while hi - lo > tol_deg:
        mid = 0.5 * (lo + hi)
        r = run(mid)
        if r.persistent_sliding:
            hi, r_hi = mid, r
        else:
            lo = mid
    return CriticalAngle(angle_deg=hi, Theta=r_hi.Theta, bracket_deg=(lo, hi), impacts=count[0], e_n=r_hi.e_n)
