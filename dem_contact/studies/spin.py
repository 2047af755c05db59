"""Impacts with out-of-plane spin: how f/mu and the rebound depend on a spin about the incident tangential
direction (which gives the contact point a velocity across the impact plane), for a scene of Wu, Thornton
& Li (2009), compared with the planar impact along the incident slip and with the BEM reference.

Frame of ``impacts.impact3d`` (z into the wall, x along the incident tangential velocity): a spin wx gives
the slip velocity a component s_y = -R wx across the impact plane, measured by
Theta_across = 2 s_y / ((1 + e_n) mu V_n) as Theta measures the in-plane one.
"""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import asdict, dataclass

import numpy as np

from ..impacts.impact import impact
from ..impacts.impact3d import impact3d
from ..laws.model import Scene


@dataclass
class SpinRow:
    law: str
    angle_deg: float
    spin_x: float                 # wx [rad/s]
    Theta: float                  # in-plane Theta of the incident slip
    Theta_across: float
    f_over_mu: float              # in-plane
    f_across_over_mu: float
    e_t: float
    Omega_r: float
    rebound_angle_deg: float
    out_of_plane_angle_deg: float
    slip_angle_i_deg: float
    slip_angle_r_deg: float
    planar_f_over_mu: float       # planar impact at the incident slip speed |s_i|
    planar_deviation: float       # |f_vec/mu - planar f/mu along the slip|


def spin_for_Theta_across(scene: Scene, vn: float, Theta_across: float) -> float:
    """wx [rad/s] giving Theta_across (with e_n = 1: elastic normal restitution assumed for the target)."""
    return -Theta_across * scene.mu * vn / scene.sphere.radius


def spin_sweep(scene: Scene, vn: float = 5.0, angles=(10.0, 30.0, 50.0), Theta_across=np.linspace(-6, 6, 25),
               *, steps_per_contact: float | None = None, label: str | None = None) -> list:
    """3D impacts at each impact angle [deg] (tangential velocity along x) with a spin wx about x chosen
    for each target Theta_across; each compared with the planar impact along its incident slip."""
    rows = []
    R = scene.sphere.radius
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ang in angles:
            vt = vn * math.tan(math.radians(ang))
            for Tx in Theta_across:
                wx = spin_for_Theta_across(scene, vn, float(Tx))
                q = impact3d(scene, vn, (vt, 0.0), (wx, 0.0, 0.0), steps_per_contact=steps_per_contact)
                s = np.array([vt, -R * wx])
                speed = float(np.hypot(*s))
                p = impact(scene, vn, speed, 0.0, steps_per_contact=steps_per_contact)
                f_vec = np.array([q.f_over_mu, q.f_across_over_mu])
                dev = float(np.hypot(*(f_vec - p.f_over_mu * s / speed))) if speed > 0 else float(np.hypot(*f_vec))
                rows.append(SpinRow(label or scene.tangential, ang, wx, q.Theta, q.Theta_across, q.f_over_mu,
                                    q.f_across_over_mu, q.e_t, q.Omega_r, q.rebound_angle_deg,
                                    q.out_of_plane_angle_deg, q.slip_angle_i_deg, q.slip_angle_r_deg,
                                    p.f_over_mu, dev))
    return rows


@dataclass
class BEMSpinRow:
    law: str
    angle_deg: float
    spin_x: float
    Theta: float
    Theta_across: float
    f_over_mu: float              # the law (impact3d)
    f_across_over_mu: float
    bem_f_over_mu: float          # the BEM (reference.impact.bem_impact)
    bem_f_across_over_mu: float
    error: float                  # |f_vec(law) - f_vec(BEM)| / mu
    out_of_plane_angle_deg: float
    bem_out_of_plane_angle_deg: float
    bem_seconds: float


def bem_spin_cases(scene: Scene, cases, vn: float = 5.0, *, n_across: int = 32, steps: int = 200,
                   laws=("mdr_adaptive", "mdr", "md")) -> list:
    """For each (angle [deg], Theta_across): the BEM impact (``reference.impact.bem_impact``, its z axis
    out of the wall: vectors mapped by y -> -y, z -> -z) and each law's impact3d at ``steps`` steps per
    contact, compared through the impulse-ratio vector f/mu."""
    from ..reference.impact import bem_impact

    rows = []
    R = scene.sphere.radius
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ang, Tacross in cases:
            vt = vn * math.tan(math.radians(ang))
            wx = spin_for_Theta_across(scene, vn, Tacross)
            t0 = time.perf_counter()
            b = bem_impact(scene, vn, (vt, 0.0), (wx, 0.0, 0.0), n_across=n_across, steps=steps)
            tb = time.perf_counter() - t0
            Pb = np.array([b.tangential_impulse[0], -b.tangential_impulse[1]])
            fb = -Pb / (b.normal_impulse * scene.mu)
            vb = np.array([b.v_r[0], -b.v_r[1]])
            vn_r = -b.e_n * vn
            bem_out = math.degrees(math.atan2(vb[1], math.hypot(vb[0], vn_r)))
            for law in laws:
                sc = Scene(scene.sphere, scene.body2, mu=scene.mu, normal=scene.normal, tangential=law,
                           v_ref=vn)
                q = impact3d(sc, vn, (vt, 0.0), (wx, 0.0, 0.0), steps_per_contact=steps)
                f = np.array([q.f_over_mu, q.f_across_over_mu])
                rows.append(BEMSpinRow(law, ang, wx, q.Theta, q.Theta_across, q.f_over_mu, q.f_across_over_mu,
                                       float(fb[0]), float(fb[1]), float(np.hypot(*(f - fb))),
                                       q.out_of_plane_angle_deg, bem_out, tb))
    return rows


def rows_to_dicts(rows) -> list:
    return [asdict(r) for r in rows]
