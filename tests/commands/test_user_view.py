"""What a user sees: the first-run message instead of a stuck progress bar, and figures that do not draw
unphysical model curves or cut the data."""
import subprocess
import sys

import numpy as np

from dem_contact import plots
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import sweep_angles
from dem_contact.rebound import models as rm


def test_compile_message_only_when_compiling(capsys):
    """The commands say they compile only when numba compiles: not in a new process whose kernels come
    from numba's cache, but around a real compilation."""
    from numba import njit

    from dem_contact.impacts import sweep as sw

    code = ("from dem_contact.impacts.presets import preset_scene\n"
            "from dem_contact.impacts.sweep import sweep_angles\n"
            "sweep_angles(preset_scene('EE', 5.0), [10.0, 20.0], 5.0, progress=True)\n")
    for _ in range(2):       # the first run fills numba's cache if it lacks the kernels; the second loads them
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
    assert "compiling" not in p.stderr
    with sw.compile_notice(True):
        njit(lambda x: x + 1)(1)                                    # a function compiled here and now
    err = capsys.readouterr().err
    assert "compiling kernels" in err and "kernels compiled in" in err
    with sw.compile_notice(True):
        sw.sweep_kernel()                                           # already loaded: nothing to compile
    assert capsys.readouterr().err == ""


def test_sweep_warnings_one_line_per_kind():
    """A warning that differs between the impacts only in its numbers is reported once, with the number of
    impacts and the range of the numbers."""
    import re
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = sweep_angles(preset_scene("EE", 5.0), [0.0, 20.0, 40.0, 60.0], 5.0, steps_per_contact=5)
    kinds = [re.sub(r"[-+]?\d[\d.e+-]*", "#", w) for w in res.warnings]
    assert len(kinds) == len(set(kinds))
    balance = [w for w in res.warnings if w.startswith("energy balance error")]
    assert len(balance) == 1 and " to " in balance[0] and balance[0].endswith(f"of {len(res)} impacts)")


def test_model_curves_blank_where_unphysical():
    """A fit with f/mu(0) < 0 would draw e_t > 1 as Theta -> 0: those parts are not drawn."""
    c = (-0.0034 - 0.6 * np.tanh(1.0), -0.6, 1.0, -0.4)      # f/mu(0) = -0.0034
    m = plots._physical(rm.wu(np.linspace(0.0, 8.0, 400), c))
    drawn = np.isfinite(m["e_t"])
    assert not drawn[0] and drawn[-1]
    assert np.all(m["e_t"][drawn] <= 1.0 + 1e-12)


def test_fixed_speed_sweep_figure_keeps_every_point(tmp_path, monkeypatch):
    """No Theta cut: the axis of a fixed-speed sweep reaches its largest Theta; the e_t axis follows the
    data."""
    res = sweep_angles(preset_scene("EE", 5.0), [5.0, 30.0, 60.0, 80.0], 5.0)
    seen = {}
    real_close = plots.plt.close

    def keep(fig):
        seen["axes"] = fig.axes
        real_close(fig)

    monkeypatch.setattr(plots.plt, "close", keep)
    plots.sweep_figure(res, tmp_path / "s.png", Theta_c={"fit": 5.7, "simulation": 5.78, "eq. 4.1": 5.786})
    f_ax, et_ax = seen["axes"][0], seen["axes"][4]
    assert f_ax.get_xlim()[1] >= np.nanmax(res.Theta) - 1e-9
    lo, hi = et_ax.get_ylim()
    assert lo <= np.nanmin(res.e_t) and hi >= np.nanmax(res.e_t) and lo > -0.6
    styles = {(tuple(l.get_color()) if not isinstance(l.get_color(), str) else l.get_color(), l.get_linestyle())
              for l in f_ax.lines if "Theta_c" in str(l.get_label())}
    assert len(styles) == 3                              # three distinct critical-angle lines
    assert "$\\Theta$" in f_ax.get_xlabel()


def test_sweep_reports_show_each_warning_once(capsys):
    """The text reports of the angle sweeps (sweep, impact3d --angles) carry their impacts' warnings, one
    line per kind with the number of impacts."""
    from dem_contact.cli import main

    for args in (["sweep", "--no-plot", "--no-progress"], ["impact3d"]):
        assert main([*args, "--angles", "0:20:10", "--steps-per-contact", "5"]) == 0
        out = capsys.readouterr().out
        coarse = [line for line in out.splitlines() if line.startswith("warning: only 5 steps per contact")]
        assert len(coarse) == 1 and coarse[0].endswith("(3 of 3 impacts)"), (args, out)
