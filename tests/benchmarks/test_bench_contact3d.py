"""Speed of the 3D contact kernels: contact updates per second on one core.

Every law runs through ``contact3d.contact_forces_serial`` (the batch loop on one thread) over
N_CONTACTS contacts of random orientation, overlap and relative velocity; each round advances every
contact by one step. The reference is the same loop for Hertz + md (Thornton-Yin Mindlin-Deresiewicz)
written in C (generated into a temp dir, gcc -O3, loaded with ctypes; skipped without gcc).

Run: ``pytest tests/benchmarks/test_bench_contact3d.py --benchmark-only``; updates/s = N_CONTACTS / mean.
"""
import ctypes
import shutil
import subprocess

import numpy as np
import pytest

from dem_contact.dem.contact3d import contact_forces_serial, new_histories
from dem_contact.laws.slots import N_HIST_BASE
from dem_contact.materials import STEEL, Material, Sphere, Wall
from dem_contact.laws.model import NORMAL_LAWS, TANGENTIAL_LAWS
from dem_contact.dem.pairs import pair_table

N_CONTACTS = 100_000
DT = 2e-7


def _workload(tangential, normal="hertz", n=N_CONTACTS):
    spheres = [Sphere(2e-3, STEEL), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0, yield_pressure=1e9))]
    tab = pair_table(spheres, [Wall(STEEL)], mu=0.4, normal=normal, tangential=tangential, e_n=0.8, v_ref=1.0)
    rng = np.random.default_rng(0)
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    vel = rng.normal(scale=0.05, size=(n, 3))
    delta = rng.uniform(1e-7, 3e-6, size=n)
    pair = rng.integers(0, tab.params.shape[0], size=n)
    H, H3 = new_histories(n, tab.history_size)
    return tab, pair, H, H3, nrm, delta, vel, np.zeros((n, 3)), np.zeros((n, 3))


def _run_numba(benchmark, tangential, normal="hertz"):
    tab, pair, H, H3, nrm, delta, vel, f, t = _workload(tangential, normal)
    args = (tab.normal_id, tab.tangential_id, tab.params, pair, H, H3, nrm, delta, vel, DT, f, t)
    contact_forces_serial(*args)              # compile / load and warm up
    benchmark.pedantic(contact_forces_serial, args=args, rounds=20, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = N_CONTACTS / benchmark.stats.stats.mean
    return N_CONTACTS / benchmark.stats.stats.mean


@pytest.mark.benchmark(group="contact3d-tangential")
@pytest.mark.parametrize("tangential", list(TANGENTIAL_LAWS))
def test_bench_batch_tangential(benchmark, tangential):
    _run_numba(benchmark, tangential)


@pytest.mark.benchmark(group="contact3d-normal")
@pytest.mark.parametrize("normal", list(NORMAL_LAWS))
def test_bench_batch_normal(benchmark, normal):
    _run_numba(benchmark, "md", normal)


C_SOURCE = r"""
#include <math.h>
enum {P_ESTAR = 0, P_GSTAR = 1, P_RSTAR = 2, P_MU = 4};
enum {H_N = 0, H_A = 1, H_T = 6, H_TS = 7, H_TSS = 8, H_REGIME = 9, H_SIGN = 10, H_XI = 11};

static double md(const double *p, double *h, double N, double dN, double a, double a_old, double dd) {
    double mu = p[P_MU], muN = mu * N;
    if (muN <= 0.0 || a <= 0.0) {
        h[H_T] = h[H_TS] = h[H_TSS] = h[H_REGIME] = h[H_SIGN] = h[H_XI] = 0.0;
        return 0.0;
    }
    double s = h[H_SIGN];
    if (s == 0.0) s = dd >= 0.0 ? 1.0 : -1.0;
    double t = s * h[H_T], ts = h[H_TS], tss = h[H_TSS];
    int k = (int)h[H_REGIME];
    double d = s * dd, mdN = mu * dN;
    if (k == 0) {
        if (d < 0.0) {
            if (t <= 0.0) { s = -s; t = -t; d = -d; } else { k = 1; ts = t; }
        }
    } else if (k == 1) {
        if (d > 0.0) { k = 2; tss = t; }
    } else if (d < 0.0) { k = 1; ts = t; }
    double am = 2.0 / 3.0 * (a_old * a_old + a_old * a + a * a) / (a_old + a);
    double kt = 8.0 * p[P_GSTAR] * am, th3, th;
    if (mdN > 0.0 && fabs(kt * d) < mdN) {
        t += kt * d;
    } else if (k == 0) {
        th3 = 1.0 - (t + mdN) / muN;
        th = pow(fmin(fmax(th3, 0.0), 1.0), 1.0 / 3.0);
        t += kt * th * d + mdN * (1.0 - th);
    } else if (k == 1) {
        th3 = 1.0 - (ts - t + 2.0 * mdN) / (2.0 * muN);
        th = pow(fmin(fmax(th3, 0.0), 1.0), 1.0 / 3.0);
        t += kt * th * d - mdN * (1.0 - th);
    } else {
        th3 = 1.0 - (t - tss + 2.0 * mdN) / (2.0 * muN);
        th = pow(fmin(fmax(th3, 0.0), 1.0), 1.0 / 3.0);
        t += kt * th * d + mdN * (1.0 - th);
    }
    ts += mdN;
    tss -= mdN;
    if (k == 1 && t < -ts) { s = -s; t = -t; k = 0; }
    else if (k == 2 && t >= ts) k = 0;
    if (fabs(t) >= muN) { if (t < 0.0) s = -s; t = muN; k = 0; }
    h[H_T] = s * t; h[H_TS] = ts; h[H_TSS] = tss; h[H_REGIME] = k; h[H_SIGN] = s;
    return s * t;
}

void batch(long n, int nhist, int nparam, const double *params, const long *pair, double *H, double *H3,
           const double *nrm, const double *delta, const double *vel, double dt, double *F, double *Ft) {
    for (long c = 0; c < n; c++) {
        const double *p = params + pair[c] * nparam;
        double *h = H + c * nhist, *h3 = H3 + 3 * c;
        double nx = nrm[3 * c], ny = nrm[3 * c + 1], nz = nrm[3 * c + 2];
        double vx = vel[3 * c], vy = vel[3 * c + 1], vz = vel[3 * c + 2];
        double vn = vx * nx + vy * ny + vz * nz;
        double ddx = (vx - vn * nx) * dt, ddy = (vy - vn * ny) * dt, ddz = (vz - vn * nz) * dt;
        double ux = h3[0], uy = h3[1], uz = h3[2];
        int axis = 0;
        if (h[H_T] != 0.0) {
            double un = ux * nx + uy * ny + uz * nz;
            ux -= un * nx; uy -= un * ny; uz -= un * nz;
            double norm = sqrt(ux * ux + uy * uy + uz * uz);
            if (norm > 0.0) { ux /= norm; uy /= norm; uz /= norm; axis = 1; }
        }
        if (!axis) {
            double dm = sqrt(ddx * ddx + ddy * ddy + ddz * ddz);
            if (dm > 0.0) { ux = ddx / dm; uy = ddy / dm; uz = ddz / dm; } else { ux = uy = uz = 0.0; }
        }
        double dpar = ddx * ux + ddy * uy + ddz * uz;
        double px = ddx - dpar * ux, py = ddy - dpar * uy, pz = ddz - dpar * uz;
        double dl = delta[c], N = 0.0, a = 0.0;
        if (dl > 0.0) { a = sqrt(p[P_RSTAR] * dl); N = 4.0 / 3.0 * p[P_ESTAR] * a * dl; }
        double Np = N > 0.0 ? N : 0.0;
        double T = md(p, h, Np, Np - h[H_N], a, h[H_A], dpar);
        h[H_N] = Np; h[H_A] = a;
        double tx = T * ux, ty = T * uy, tz = T * uz;
        if (T != 0.0 && (px != 0.0 || py != 0.0 || pz != 0.0)) {
            double k0 = 8.0 * p[P_GSTAR] * a;
            double wx = tx + k0 * px, wy = ty + k0 * py, wz = tz + k0 * pz;
            double inv = 1.0 / sqrt(wx * wx + wy * wy + wz * wz);
            if (T < 0.0) inv = -inv;
            ux = wx * inv; uy = wy * inv; uz = wz * inv;
            tx = T * ux; ty = T * uy; tz = T * uz;
        }
        h3[0] = ux; h3[1] = uy; h3[2] = uz;
        F[3 * c] = -N * nx - tx; F[3 * c + 1] = -N * ny - ty; F[3 * c + 2] = -N * nz - tz;
        Ft[3 * c] = -tx; Ft[3 * c + 1] = -ty; Ft[3 * c + 2] = -tz;
    }
}
"""


@pytest.fixture(scope="module")
def c_batch(tmp_path_factory):
    gcc = shutil.which("gcc")
    if gcc is None:
        pytest.skip("gcc not found")
    d = tmp_path_factory.mktemp("cref")
    (d / "ref.c").write_text(C_SOURCE)
    lib = d / "libref.so"
    subprocess.run([gcc, "-O3", "-march=native", "-shared", "-fPIC", str(d / "ref.c"), "-o", str(lib), "-lm"],
                   check=True)
    f = ctypes.CDLL(str(lib)).batch
    f.restype = None
    return f


def _ptr(a):
    return a.ctypes.data_as(ctypes.c_void_p)


@pytest.mark.benchmark(group="contact3d-c-reference")
def test_bench_c_reference_hertz_md(benchmark, c_batch):
    """Hertz + md in C; also checks that C and numba give the same forces (same operations)."""
    tab, pair, H, H3, nrm, delta, vel, f, t = _workload("md")
    assert tab.history_size == N_HIST_BASE
    pair = pair.astype(np.int64)
    Hn, H3n, fn, tn = H.copy(), H3.copy(), f.copy(), t.copy()
    args = (ctypes.c_long(N_CONTACTS), ctypes.c_int(H.shape[1]), ctypes.c_int(tab.params.shape[1]),
            _ptr(tab.params), _ptr(pair), _ptr(H), _ptr(H3), _ptr(nrm), _ptr(delta), _ptr(vel),
            ctypes.c_double(DT), _ptr(f), _ptr(t))
    for _ in range(3):
        c_batch(*args)
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, pair, Hn, H3n, nrm, delta, vel, DT, fn, tn)
    scale = np.abs(fn).max()
    assert np.abs(f - fn).max() <= 1e-12 * scale
    benchmark.pedantic(c_batch, args=args, rounds=20, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = N_CONTACTS / benchmark.stats.stats.mean


@pytest.mark.benchmark(group="contact3d-c-reference")
def test_bench_numba_hertz_md(benchmark):
    """The numba counterpart of test_bench_c_reference_hertz_md (ratio = C time / this time)."""
    _run_numba(benchmark, "md")
