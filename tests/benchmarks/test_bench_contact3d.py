"""Speed of the 3D contact kernels: contact updates per second on one core.

Every law runs through ``contact3d.contact_forces_serial`` (the batch loop on one thread) over
N_CONTACTS contacts of random orientation, overlap and relative velocity; each round advances every
contact by one step (random mean spins about the normal, so the history is turned every step). Group
``contact3d``: the numba kernels against C references of the same arithmetic (Hertz + md, Hertz +
mdr_adaptive; generated into a temp dir, gcc -O3 -march=native, loaded with ctypes; skipped without gcc).

Run: ``pytest tests/benchmarks/test_bench_contact3d.py --benchmark-only --benchmark-group-by=group``;
updates/s = N_CONTACTS / min (the machine is shared: compare minima of the same run).
"""
import ctypes
import shutil
import subprocess

import numpy as np
import pytest

from dem_contact.dem.contact3d import batch_loop, contact_forces_serial, new_histories
from dem_contact.materials import STEEL, Material, Sphere, Wall
from dem_contact.laws.model import NORMAL_LAWS, TANGENTIAL_LAWS
from dem_contact.dem.pairs import pair_table
from dem_contact.laws import slots
from dem_contact.laws.model import reference_speed

N_CONTACTS = 100_000
DT = 2e-7
ROUNDS = 30


def _workload(tangential, normal="hertz", n=N_CONTACTS):
    steel = Material(E=STEEL.E, nu=STEEL.nu, rho=STEEL.rho, yield_pressure=2.5e9)    # (thornton yields at p_y)
    spheres = [Sphere(2e-3, steel), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0, yield_pressure=1e9))]
    e_n = 0.8 if normal in ("hertz_damped", "linear") else None
    tab = pair_table(spheres, [Wall(steel)], mu=0.4, normal=normal, tangential=tangential, e_n=e_n, v_ref=reference_speed(1.0))
    rng = np.random.default_rng(0)
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    vel = rng.normal(scale=0.05, size=(n, 3))
    delta = rng.uniform(1e-7, 3e-6, size=n)
    wn = rng.normal(scale=100.0, size=n)          # mean spin about the normal [rad/s]
    pair = rng.integers(0, tab.params.shape[0], size=n)
    H = new_histories(n, tab.history_size)
    return tab, pair, H, nrm, delta, vel, wn, np.zeros((n, 3)), np.zeros((n, 3))


def _run_numba(benchmark, tangential, normal="hertz"):
    tab, pair, H, nrm, delta, vel, wn, f, t = _workload(tangential, normal)
    args = (tab.normal_id, tab.tangential_id, tab.params, pair, H, nrm, delta, vel, wn, DT, f, t)
    contact_forces_serial(*args)              # compile / load and warm up
    benchmark.pedantic(contact_forces_serial, args=args, rounds=ROUNDS, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = N_CONTACTS / benchmark.stats.stats.min


@pytest.mark.benchmark(group="contact3d-tangential")
@pytest.mark.parametrize("tangential", list(TANGENTIAL_LAWS))
def test_bench_batch_tangential(benchmark, tangential):
    _run_numba(benchmark, tangential)


@pytest.mark.benchmark(group="contact3d-normal")
@pytest.mark.parametrize("normal", list(NORMAL_LAWS))
def test_bench_batch_normal(benchmark, normal):
    _run_numba(benchmark, "md", normal)


def _pressed_like(tangential, n=12_500, slots=12, rounds=40):
    """Contacts of a dense packing as a DEM engine steps them (as in ``lammps_throughput.py --scene pressed``):
    history rows scattered over ``slots`` rows per contact, the overlap oscillating by 2% and a small
    reversing slip (|dd| / a about 1e-3 per step), the contact frame turning slowly. Returns a function
    stepping every contact once (the next round of the path at each call)."""
    steel = Material(E=STEEL.E, nu=STEEL.nu, rho=STEEL.rho)
    tab = pair_table([Sphere(2e-3, steel)], [Wall(steel)], mu=0.4, tangential=tangential)
    rng = np.random.default_rng(0)
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    d0 = rng.uniform(1e-6, 3e-6, size=n)
    ph = rng.uniform(0.0, 2.0 * np.pi, n)
    H = new_histories(n * slots, tab.history_size)
    rows = rng.permutation(n * slots)[:n].astype(np.int64)
    pair = np.zeros(n, np.int64)
    wn = rng.normal(scale=1.0, size=n)
    deltas = [d0 * (1.0 + 0.02 * np.sin(ph + 0.3 * r)) for r in range(rounds)]
    vels = [rng.normal(scale=0.01, size=(n, 3)) + 0.01 * np.sin(0.3 * r + ph)[:, None] for r in range(rounds)]
    f, t = np.zeros((n, 3)), np.zeros((n, 3))
    loop = batch_loop(tab.normal_id, tab.tangential_id)
    none3 = np.zeros((0, 3))
    state = [0]

    def step():
        r = state[0] % rounds
        state[0] += 1
        loop(tab.normal_id, tab.tangential_id, tab.params, pair, H, rows, nrm, deltas[r], vels[r], none3, wn, 1e-7,
             f, t, none3)
    return step


@pytest.mark.benchmark(group="contact3d-pressed")
@pytest.mark.parametrize("tangential", ["mdr_adaptive", "mindlin_total"])
def test_bench_pressed_like(benchmark, tangential):
    """The default law and mindlin_total on the contacts of a dense packing (``_pressed_like``)."""
    step = _pressed_like(tangential)
    for _ in range(10):                 # compile, and let the histories settle into the path
        step()
    benchmark.pedantic(step, rounds=ROUNDS, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = 12_500 / benchmark.stats.stats.min


# The C references: Hertz + md and Hertz + mdr_adaptive (the default law), the arithmetic of
# laws.vector and contact3d.contact_force transcribed line by line (hertz base b = 2); the slots of the
# parameter row are the generated ones (laws.slots), filled in by _c_source.
C_SOURCE = r"""
#include <math.h>
enum {P_ESTAR = @P_ESTAR@, P_GSTAR = @P_GSTAR@, P_RSTAR = @P_RSTAR@, P_MU = @P_MU@, P_NSPRING = @P_NSPRING@};
enum {V_N = 0, V_A = 1, B = 2};
enum {W_WORK = 0, W_X = 1, W_Y = 2, W_Z = 3, M_T = 4, M_TS = 5, M_TSS = 6, M_REGIME = 7, M_SIGN = 8, N_MD = 9,
      R_T1 = 4, R_T2 = 5, R_DX = 6, R_LAZY = 7, R_D1 = 8, R_D2 = 9, R_SV1 = 10, R_SV2 = 11, R_KS = 12, R_G0 = 13,
      R_CELLS = 14, LAZY_MIN = 2};
#define NEAR (1.0 - 1e-9)
#define QNEAR (1.0 - 1e-9)

static inline void carry_unit(double *x, double *y, double *z, double nx, double ny, double nz,
                              double cs, double sn) {
    double un = *x * nx + *y * ny + *z * nz;
    double X = *x - un * nx, Y = *y - un * ny, Z = *z - un * nz;
    double p2 = X * X + Y * Y + Z * Z;
    if (p2 <= 0.0) { *x = *y = *z = 0.0; return; }
    double s = 1.0 / sqrt(p2);
    X *= s; Y *= s; Z *= s;
    if (sn != 0.0) {
        double tx = X * cs + (ny * Z - nz * Y) * sn, ty = Y * cs + (nz * X - nx * Z) * sn,
               tz = Z * cs + (nx * Y - ny * X) * sn;
        X = tx; Y = ty; Z = tz;
    }
    *x = X; *y = Y; *z = Z;
}

static double md_scalar(const double *p, double *h, double N, double dN, double a, double a_old, double dd) {
    double mu = p[P_MU], muN = mu * N;
    if (muN <= 0.0 || a <= 0.0) {
        for (int j = M_T; j < N_MD; j++) h[B + j] = 0.0;
        return 0.0;
    }
    double s = h[B + M_SIGN];
    if (s == 0.0) s = dd >= 0.0 ? 1.0 : -1.0;
    double t = s * h[B + M_T], ts = h[B + M_TS], tss = h[B + M_TSS];
    int k = (int)h[B + M_REGIME];
    double d = s * dd, mdN = mu * dN;
    if (k == 0) {
        if (d < 0.0) {
            if (t <= 0.0) { s = -s; t = -t; d = -d; } else { k = 1; ts = t; }
        }
    } else if (k == 1) {
        if (d > 0.0) { k = 2; tss = t; }
    } else if (d < 0.0) { k = 1; ts = t; }
    double kt = 8.0 * p[P_GSTAR] * (2.0 / 3.0 * (a_old * a_old + a_old * a + a * a) / (a_old + a)), th;
    if (mdN > 0.0 && fabs(kt * d) < mdN) {
        t += kt * d;
    } else if (k == 0) {
        th = cbrt(fmin(fmax(1.0 - (t + mdN) / muN, 0.0), 1.0));
        t += kt * th * d + mdN * (1.0 - th);
    } else if (k == 1) {
        th = cbrt(fmin(fmax(1.0 - (ts - t + 2.0 * mdN) / (2.0 * muN), 0.0), 1.0));
        t += kt * th * d - mdN * (1.0 - th);
    } else {
        th = cbrt(fmin(fmax(1.0 - (t - tss + 2.0 * mdN) / (2.0 * muN), 0.0), 1.0));
        t += kt * th * d + mdN * (1.0 - th);
    }
    ts += mdN;
    tss -= mdN;
    if (k == 1 && t < -ts) { s = -s; t = -t; k = 0; }
    else if (k == 2 && t >= ts) k = 0;
    if (fabs(t) >= muN) { if (t < 0.0) s = -s; t = muN; k = 0; }
    h[B + M_T] = s * t; h[B + M_TS] = ts; h[B + M_TSS] = tss; h[B + M_REGIME] = k; h[B + M_SIGN] = s;
    return s * t;
}

static void md_axis(const double *p, double *h, double N, double dN, double a, double a_old, double nx,
                    double ny, double nz, double ddx, double ddy, double ddz, double cs, double sn,
                    double *Tx, double *Ty, double *Tz) {
    double t_old = h[B + M_T], ux = 0.0, uy = 0.0, uz = 0.0;
    if (t_old != 0.0) {
        ux = h[B + W_X]; uy = h[B + W_Y]; uz = h[B + W_Z];
        carry_unit(&ux, &uy, &uz, nx, ny, nz, cs, sn);
    }
    if (ux == 0.0 && uy == 0.0 && uz == 0.0) {
        t_old = 0.0;
        double dm = sqrt(ddx * ddx + ddy * ddy + ddz * ddz);
        if (dm > 0.0) { ux = ddx / dm; uy = ddy / dm; uz = ddz / dm; }
    }
    double dpar = ddx * ux + ddy * uy + ddz * uz;
    double px = ddx - dpar * ux, py = ddy - dpar * uy, pz = ddz - dpar * uz;
    double T = md_scalar(p, h, N, dN, a, a_old, dpar);
    if (T != 0.0 && (px != 0.0 || py != 0.0 || pz != 0.0)) {
        double k0 = 8.0 * p[P_GSTAR] * a;
        double wx = T * ux + k0 * px, wy = T * uy + k0 * py, wz = T * uz + k0 * pz;
        double inv = 1.0 / sqrt(wx * wx + wy * wy + wz * wz);
        if (T < 0.0) inv = -inv;
        ux = wx * inv; uy = wy * inv; uz = wz * inv;
    }
    h[B + W_X] = ux; h[B + W_Y] = uy; h[B + W_Z] = uz;
    h[B + W_WORK] += 0.5 * (t_old * dpar + T * (ux * ddx + uy * ddy + uz * ddz));
    *Tx = T * ux; *Ty = T * uy; *Tz = T * uz;
}

static inline int ncells(double r, double dx, int n) {
    if (r <= 0.0) return 0;
    int m = (int)(r / dx) + 1;
    return m < n ? m : n;
}

static inline int ncells_q(double r, double q, int n) {
    if (r <= 0.0) return 0;
    int m = (int)q + 1;
    return m < n ? m : n;
}

static inline void radial(double *u1, double *u2, double umax) {
    double m2 = *u1 * *u1 + *u2 * *u2;
    if (m2 > umax * umax) { double s = umax / sqrt(m2); *u1 *= s; *u2 *= s; }
}

static void mdr_cells(const double *p, double *h, int k0, int n, double dx, double N, double a, double a_old,
                      double d1, double d2, double *T1o, double *T2o) {
    double GM = 4.0 * p[P_GSTAR];
    double umax_per_w = 3.0 * p[P_MU] * N / (16.0 * p[P_GSTAR] * a * a * a);
    double a2 = a * a, da = a - a_old;
    double idx = 1.0 / dx, qa = a * idx, qo = a_old * idx;
    int m1 = ncells_q(a, qa, n), m2 = ncells_q(a_old, qo, n);
    int m = m1 > m2 ? m1 : m2;
    int full = (int)fmin(qa, qo);
    if (full > m) full = m;
    double dx2 = dx * dx / 3.0, S1 = 0.0, S2 = 0.0, L1 = 0.0, L2 = 0.0;
    int lazy = (int)h[B + R_LAZY];
    if (lazy > 0) {                       /* the sticking zone: one common increment, if provably sticking */
        double D1 = h[B + R_D1] + d1, D2 = h[B + R_D2] + d2, Ks = h[B + R_KS], G0 = h[B + R_G0];
        double wl = 3.0 * (lazy - 1) * lazy + 1.0;
        double e = fmin(QNEAR * umax_per_w * (a2 - dx2) - G0 + Ks * dx2,
                        QNEAR * umax_per_w * (a2 - dx2 * wl) - G0 + Ks * dx2 * wl);
        if (e >= 0.0 && e * e >= D1 * D1 + D2 * D2) {
            h[B + R_D1] = D1; h[B + R_D2] = D2;
            L1 = h[B + R_SV1] + lazy * D1; L2 = h[B + R_SV2] + lazy * D2;
        } else {
            D1 -= d1; D2 -= d2;
            for (int i = 0; i < lazy; i++) { h[k0 + 2 * i] += D1; h[k0 + 2 * i + 1] += D2; }
            lazy = 0;
            for (int j = R_LAZY; j < R_CELLS; j++) h[B + j] = 0.0;
        }
    }
    int near = 0, i0 = full;
    for (int i = lazy; i < full; i++) {     /* u += d; flag a cell near or beyond its circle */
        int k = k0 + 2 * i;
        double umax = umax_per_w * (a2 - dx2 * (3 * i * (i + 1) + 1));
        double u1 = h[k] + d1, u2 = h[k + 1] + d2;
        h[k] = u1; h[k + 1] = u2;
        S1 += u1; S2 += u2;
        near |= u1 * u1 + u2 * u2 > NEAR * (umax * umax);
    }
    if (near) {                           /* cells before the first flagged one keep their values */
        S1 = 0.0; S2 = 0.0;
        for (i0 = lazy; i0 < full; i0++) {
            int k = k0 + 2 * i0;
            double umax = umax_per_w * (a2 - dx2 * (3 * i0 * (i0 + 1) + 1));
            if (h[k] * h[k] + h[k + 1] * h[k + 1] > NEAR * (umax * umax)) break;
            S1 += h[k]; S2 += h[k + 1];
        }
        for (int i = i0; i < full; i++) {  /* radial return from there on */
            int k = k0 + 2 * i;
            double umax = umax_per_w * (a2 - dx2 * (3 * i * (i + 1) + 1));
            double u1 = h[k], u2 = h[k + 1];
            radial(&u1, &u2, umax);
            h[k] = u1; h[k + 1] = u2;
            S1 += u1; S2 += u2;
        }
    }
    if (lazy == 0 && i0 >= LAZY_MIN) {    /* a new sticking zone: the cells before the first one near */
        double smin = INFINITY, V1 = 0.0, V2 = 0.0;
        for (int i = 0; i < i0; i++) {
            int k = k0 + 2 * i;
            double umax = umax_per_w * (a2 - dx2 * (3 * i * (i + 1) + 1));
            V1 += h[k]; V2 += h[k + 1];
            smin = fmin(smin, umax - sqrt(h[k] * h[k] + h[k + 1] * h[k + 1]));
        }
        h[B + R_LAZY] = i0; h[B + R_D1] = 0.0; h[B + R_D2] = 0.0; h[B + R_SV1] = V1; h[B + R_SV2] = V2;
        h[B + R_KS] = umax_per_w; h[B + R_G0] = umax_per_w * a2 - smin;
    }
    S1 += L1; S2 += L2;
    double T1 = S1 * dx, T2 = S2 * dx;
    for (int i = full; i < m; i++) {
        int k = k0 + 2 * i;
        double x0 = i * dx;
        double l_new = fmin(fmax(a - x0, 0.0), dx);
        if (l_new <= 0.0) { h[k] = 0.0; h[k + 1] = 0.0; continue; }
        double l_old = fmin(fmax(a_old - x0, 0.0), dx);
        double u1 = h[k] + d1, u2 = h[k + 1] + d2;
        if (l_new > l_old) {
            double xm = x0 + 0.5 * (l_old + l_new);
            double f = (a - xm) / da * (l_new - l_old);
            double il = 1.0 / l_new;
            u1 = (u1 * l_old + d1 * f) * il;
            u2 = (u2 * l_old + d2 * f) * il;
        }
        double x1 = x0 + l_new;
        radial(&u1, &u2, umax_per_w * (a2 - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0));
        h[k] = u1; h[k + 1] = u2;
        T1 += u1 * l_new; T2 += u2 * l_new;
    }
    *T1o = T1 * (2.0 * GM); *T2o = T2 * (2.0 * GM);
}

static void mdr_merge(double *h, int k0, int n, double dx, double r) {
    for (int j = 0; j < n / 2; j++) {
        double x0 = 2 * j * dx;
        double l0 = fmin(fmax(r - x0, 0.0), dx), l1 = fmin(fmax(r - x0 - dx, 0.0), dx);
        double u1 = 0.0, u2 = 0.0;
        if (l0 + l1 > 0.0) {
            u1 = (h[k0 + 4 * j] * l0 + h[k0 + 4 * j + 2] * l1) / (l0 + l1);
            u2 = (h[k0 + 4 * j + 1] * l0 + h[k0 + 4 * j + 3] * l1) / (l0 + l1);
        }
        h[k0 + 2 * j] = u1; h[k0 + 2 * j + 1] = u2;
    }
    for (int j = 2 * (n / 2); j < 2 * n; j++) h[k0 + j] = 0.0;
}

static inline double wbar(double r, double x0, double x1) { return r * r - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0; }

static inline void halves(double u, double r, double x0, double hdx, double *u0, double *u1) {
    double l0 = fmin(fmax(r - x0, 0.0), hdx), l1 = fmin(fmax(r - x0 - hdx, 0.0), hdx);
    *u0 = 0.0; *u1 = 0.0;
    if (u != 0.0 && l0 > 0.0) {
        double wc = wbar(r, x0, x0 + l0 + l1);
        if (wc > 0.0) {
            *u0 = u * wbar(r, x0, x0 + l0) / wc;
            if (l1 > 0.0) *u1 = u * wbar(r, x0 + hdx, x0 + hdx + l1) / wc;
        } else {
            *u0 = u;
        }
    }
}

static void mdr_split(double *h, int k0, int n, double dx, double r) {
    double hdx = 0.5 * dx;
    for (int j = n / 2 - 1; j >= 0; j--) {
        double u10, u11, u20, u21;
        halves(h[k0 + 2 * j], r, j * dx, hdx, &u10, &u11);
        halves(h[k0 + 2 * j + 1], r, j * dx, hdx, &u20, &u21);
        h[k0 + 4 * j] = u10; h[k0 + 4 * j + 1] = u20; h[k0 + 4 * j + 2] = u11; h[k0 + 4 * j + 3] = u21;
    }
}

static void mdr_shrink_edge(double *h, int k0, int n, double dx, double a, double a_old) {
    int i = (int)(a * (1.0 / dx));   /* (the numba kernel reuses a / dx of the cell counts) */
    if (i >= n) return;
    double x0 = i * dx, l_new = a - x0, l_old = fmin(a_old - x0, dx);
    if (l_new > 0.0 && l_old > l_new) {
        double x1 = x0 + l_old;
        double w_old = 3.0 * a_old * a_old - (x0 * x0 + x0 * x1 + x1 * x1);
        if (w_old > 0.0) {
            double f = (3.0 * a_old * a_old - (x0 * x0 + x0 * a + a * a)) / w_old;
            h[k0 + 2 * i] *= f; h[k0 + 2 * i + 1] *= f;
        }
    }
}

static void mdr_adaptive(const double *p, double *h, double N, double a, double a_old, double nx, double ny,
                         double nz, double ddx, double ddy, double ddz, double cs, double sn,
                         double *Tx, double *Ty, double *Tz) {
    int n = (int)p[P_NSPRING], k0 = B + R_CELLS;
    double dx = h[B + R_DX];
    if (N <= 0.0 || a * a * a <= 0.0) {
        if (dx > 0.0) {
            int m1 = ncells(a, dx, n), m2 = ncells(a_old, dx, n);
            for (int j = 0; j < 2 * (m1 > m2 ? m1 : m2); j++) h[k0 + j] = 0.0;
        }
        for (int j = W_X; j < R_CELLS; j++) h[B + j] = 0.0;
        *Tx = *Ty = *Tz = 0.0;
        return;
    }
    double ex = h[B + W_X], ey = h[B + W_Y], ez = h[B + W_Z];
    carry_unit(&ex, &ey, &ez, nx, ny, nz, cs, sn);
    if (ex == 0.0 && ey == 0.0 && ez == 0.0) {
        ex = ddx; ey = ddy; ez = ddz;
        carry_unit(&ex, &ey, &ez, nx, ny, nz, 1.0, 0.0);
        if (ex == 0.0 && ey == 0.0 && ez == 0.0) {
            if (fabs(nx) < 0.9) { ex = 1.0; ey = 0.0; ez = 0.0; } else { ex = 0.0; ey = 1.0; ez = 0.0; }
            carry_unit(&ex, &ey, &ez, nx, ny, nz, 1.0, 0.0);
        }
    }
    double fx = ny * ez - nz * ey, fy = nz * ex - nx * ez, fz = nx * ey - ny * ex;
    double d1 = ddx * ex + ddy * ey + ddz * ez, d2 = ddx * fx + ddy * fy + ddz * fz;
    int lazy = (int)h[B + R_LAZY];
    if (lazy > 0 && (a > n * dx || 4.0 * a < n * dx || fmin(a, a_old) < lazy * dx)) {
        double D1 = h[B + R_D1], D2 = h[B + R_D2];   /* the zone's cells take u = v + D first */
        for (int i = 0; i < lazy; i++) { h[k0 + 2 * i] += D1; h[k0 + 2 * i + 1] += D2; }
        for (int j = R_LAZY; j < R_CELLS; j++) h[B + j] = 0.0;
    }
    if (dx <= 0.0 || a_old <= 0.0) {
        for (int j = 0; j < 2 * n; j++) h[k0 + j] = 0.0;
        a_old = 0.0;
        double L = p[P_RSTAR] > 0.0 ? p[P_RSTAR] : 1.0;
        dx = L * pow(2.0, floor(log2(2.0 * a / (n * L))));
    }
    while (a > n * dx) { mdr_merge(h, k0, n, dx, a_old); dx *= 2.0; }
    while (4.0 * a < n * dx && 4.0 * a_old < n * dx) { mdr_split(h, k0, n, dx, a_old); dx *= 0.5; }
    h[B + R_DX] = dx;
    if (a < a_old) mdr_shrink_edge(h, k0, n, dx, a, a_old);
    double T1, T2;
    mdr_cells(p, h, k0, n, dx, N, a, a_old, d1, d2, &T1, &T2);
    h[B + W_WORK] += 0.5 * ((h[B + R_T1] + T1) * d1 + (h[B + R_T2] + T2) * d2);
    h[B + W_X] = ex; h[B + W_Y] = ey; h[B + W_Z] = ez;
    h[B + R_T1] = T1; h[B + R_T2] = T2;
    *Tx = T1 * ex + T2 * fx; *Ty = T1 * ey + T2 * fy; *Tz = T1 * ez + T2 * fz;
}

void batch(int law, long n, int nhist, int nparam, const double *params, const long *pair, double *H,
           const double *nrm, const double *delta, const double *vel, const double *wn, double dt,
           double *F, double *Ft) {
    for (long c = 0; c < n; c++) {
        const double *p = params + pair[c] * nparam;
        double *h = H + c * nhist;
        double nx = nrm[3 * c], ny = nrm[3 * c + 1], nz = nrm[3 * c + 2];
        double vx = vel[3 * c], vy = vel[3 * c + 1], vz = vel[3 * c + 2];
        double vn = vx * nx + vy * ny + vz * nz;
        double ddx = (vx - vn * nx) * dt, ddy = (vy - vn * ny) * dt, ddz = (vz - vn * nz) * dt;
        double cs = 1.0, sn = 0.0;
        if (wn[c] != 0.0) {
            double q = 0.5 * wn[c] * dt, inv = 1.0 / (1.0 + q * q);
            cs = (1.0 - q * q) * inv;
            sn = 2.0 * q * inv;
        }
        double dl = delta[c], N = 0.0, a = 0.0;
        if (dl > 0.0) { a = sqrt(p[P_RSTAR] * dl); N = 4.0 / 3.0 * p[P_ESTAR] * a * dl; }
        double Np = N > 0.0 ? N : 0.0, tx, ty, tz;
        if (law == 0)
            md_axis(p, h, Np, Np - h[V_N], a, h[V_A], nx, ny, nz, ddx, ddy, ddz, cs, sn, &tx, &ty, &tz);
        else
            mdr_adaptive(p, h, Np, a, h[V_A], nx, ny, nz, ddx, ddy, ddz, cs, sn, &tx, &ty, &tz);
        h[V_N] = Np; h[V_A] = a;
        F[3 * c] = -N * nx - tx; F[3 * c + 1] = -N * ny - ty; F[3 * c + 2] = -N * nz - tz;
        Ft[3 * c] = -tx; Ft[3 * c + 1] = -ty; Ft[3 * c + 2] = -tz;
    }
}
"""


def _c_source():
    """C_SOURCE with the slot numbers of the parameter row (``laws.slots``)."""
    src = C_SOURCE
    for name in ("P_ESTAR", "P_GSTAR", "P_RSTAR", "P_MU", "P_NSPRING"):
        src = src.replace(f"@{name}@", str(getattr(slots, name)))
    return src


C_LAWS = {"md": 0, "mdr_adaptive": 1}


@pytest.fixture(scope="module")
def c_batch(tmp_path_factory):
    gcc = shutil.which("gcc")
    if gcc is None:
        pytest.skip("gcc not found")
    d = tmp_path_factory.mktemp("cref")
    (d / "ref.c").write_text(_c_source())
    lib = d / "libref.so"
    subprocess.run([gcc, "-O3", "-march=native", "-shared", "-fPIC", str(d / "ref.c"), "-o", str(lib), "-lm"],
                   check=True)
    f = ctypes.CDLL(str(lib)).batch
    f.restype = None
    return f


def _ptr(a):
    return a.ctypes.data_as(ctypes.c_void_p)


def _run_c(benchmark, c_batch, tangential):
    """The C loop; first checks that C and numba give the same forces and histories (same operations)."""
    tab, pair, H, nrm, delta, vel, wn, f, t = _workload(tangential)
    Hn, fn, tn = H.copy(), f.copy(), t.copy()
    args = (ctypes.c_int(C_LAWS[tangential]), ctypes.c_long(N_CONTACTS), ctypes.c_int(H.shape[1]),
            ctypes.c_int(tab.params.shape[1]), _ptr(tab.params), _ptr(pair), _ptr(H), _ptr(nrm), _ptr(delta),
            _ptr(vel), _ptr(wn), ctypes.c_double(DT), _ptr(f), _ptr(t))
    for _ in range(3):
        c_batch(*args)
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, pair, Hn, nrm, delta, vel, wn, DT, fn,
                              tn)
    assert np.abs(f - fn).max() <= 1e-12 * np.abs(fn).max()
    assert np.abs(t - tn).max() <= 1e-12 * np.abs(tn).max()
    benchmark.pedantic(c_batch, args=args, rounds=ROUNDS, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = N_CONTACTS / benchmark.stats.stats.min


#: the laws measured against C: Hertz + md, and Hertz + mdr_adaptive (the default vector law)
C_COMPARED = ["md", "mdr_adaptive"]


@pytest.mark.benchmark(group="contact3d")
@pytest.mark.parametrize("tangential", C_COMPARED)
def test_c(benchmark, c_batch, tangential):
    """Hertz + the law in C (the reference of test_numba with the same law)."""
    _run_c(benchmark, c_batch, tangential)


@pytest.mark.benchmark(group="contact3d")
@pytest.mark.parametrize("tangential", C_COMPARED)
def test_numba(benchmark, tangential):
    """Hertz + the law, numba serial batch (ratio: min time of test_c / min time of this, same law)."""
    _run_numba(benchmark, tangential)


# The twist and rolling engine models: the default law and mindlin_total, without them (no spins), with the
# relative spins passed but no model, and with twist sds + rolling sds and twist marshall + rolling sds
# (bytes per contact: 8 * PairTable.history_size, in extra_info).
TORQUE_MODELS = {
    "none": {},
    "spins_only": {},
    "twist_sds_rolling_sds": dict(twist="sds", k_twist=1e-3, gamma_twist=1e-9, mu_twist=1e-4, rolling="sds",
                                  k_roll=1e4, gamma_roll=1e-3, mu_roll=0.1),
    "twist_marshall_rolling_sds": dict(twist="marshall", rolling="sds", k_roll=1e4, gamma_roll=1e-3, mu_roll=0.1),
}


@pytest.mark.benchmark(group="contact3d-twist-rolling")
@pytest.mark.parametrize("models", list(TORQUE_MODELS))
@pytest.mark.parametrize("tangential", ["mdr_adaptive", "mindlin_total"])
def test_bench_batch_twist_rolling(benchmark, tangential, models):
    steel = Material(E=STEEL.E, nu=STEEL.nu, rho=STEEL.rho)
    tab = pair_table([Sphere(2e-3, steel), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0))], [Wall(steel)],
                     mu=0.4, tangential=tangential, v_ref=reference_speed(1.0), **TORQUE_MODELS[models])
    rng = np.random.default_rng(0)
    n = N_CONTACTS
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    vel = rng.normal(scale=0.05, size=(n, 3))
    delta = rng.uniform(1e-7, 3e-6, size=n)
    wn = rng.normal(scale=100.0, size=n)
    pair = rng.integers(0, tab.params.shape[0], size=n)
    H = new_histories(n, tab.history_size)
    spins = rng.normal(scale=100.0, size=(n, 3)) if models != "none" else None
    torques = np.zeros((n, 3)) if models != "none" else None
    args = (tab.normal_id, tab.tangential_id, tab.params, pair, H, nrm, delta, vel, wn, DT, np.zeros((n, 3)),
            np.zeros((n, 3)))
    kw = dict(spins=spins, torques=torques)
    contact_forces_serial(*args, **kw)              # compile / load and warm up
    benchmark.pedantic(contact_forces_serial, args=args, kwargs=kw, rounds=ROUNDS, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = N_CONTACTS / benchmark.stats.stats.min
    benchmark.extra_info["bytes_per_contact"] = 8 * tab.history_size
