"""A failure inside a compiled kernel (numba reports some as SystemError, from a parallel region) is a
NumericalError from the Python API and one line from the CLI, never a result nor a traceback."""
import pytest

import dem_contact.impacts.sweep as sweep_mod
from dem_contact import NumericalError, cli, impact
from dem_contact.impacts import impact as impact_mod
from dem_contact.impacts.presets import preset_scene


def _failing(*args):
    raise SystemError("<numba.core.cpu.CPUContext> returned a result with an exception set")


def test_sweep_kernel_failure_is_a_numerical_error(monkeypatch):
    monkeypatch.setattr(sweep_mod, "sweep_kernel", lambda: _failing)
    with pytest.raises(NumericalError, match="SystemError"):
        sweep_mod.sweep_angles(preset_scene("EE", 5.0), [10.0, 20.0], 5.0)


def test_impact_kernel_failure_is_a_numerical_error(monkeypatch):
    scene = preset_scene("EE", 5.0, mu=0.2)
    consts = impact_mod.scene_constants(scene)
    monkeypatch.setattr(consts, "integrate", _failing)
    with pytest.raises(NumericalError, match="SystemError"):
        impact(scene, vn=5.0, vt=1.0)


@pytest.mark.parametrize("exc, code", [(SystemError("x"), 1), (ZeroDivisionError("x"), 1), (OSError("x"), 2)])
def test_cli_failure_is_one_line(monkeypatch, capsys, exc, code):
    def run(args):
        raise exc
    parser = cli.build_parser()
    args = parser.parse_args(["warmup"])
    monkeypatch.setattr(cli, "build_parser", lambda: type("P", (), {"parse_args": lambda self, a: args})())
    args.run = run
    assert cli.main(["warmup"]) == code
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("dem-contact warmup: ") and "Traceback" not in err
