"""Run by test_plugin.py as ``python tests/lammps/plugin_errors.py DIR``: bad input to pair_style dem/contact
and fix dem/contact/wall,
each case in a new LAMMPS instance; prints one JSON object {case: LAMMPS's error message, or None where the
input ran}."""
import json
import os
import subprocess
import sys

from dem_contact.dem.pairs import pair_table
from dem_contact.lammps import new_lammps, plugin_build, table_file
from dem_contact.materials import Material, Sphere, Wall

OUT = sys.argv[1]
R = 1e-3
MAT = Material(E=5e7, nu=0.3, rho=2500.0)


def good_table(name="t.json", walls=(), **kw):
    return table_file.save(pair_table([Sphere(R, MAT)], list(walls), mu=0.5, tangential="mindlin_total", **kw),
                           os.path.join(OUT, name))


def edited(name, edit):
    with open(good_table()) as f:
        doc = json.load(f)
    edit(doc)
    path = os.path.join(OUT, name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def scene(table, style="sphere", pair="pair_style dem/contact vmax 1.0", dt=1e-6, vel=True, plugin=None,
          units="si", gap=-2e-5, steps=10, speed=0.0, wall=None, wall_first=False, extra=(), warnings=False):
    """Two spheres touching (overlap -gap) in a box, with the fix dem/contact/wall of the words ``wall`` after
    the pair style (or before it: wall_first) and the commands ``extra`` before the run; returns the error
    message or None (warnings: LAMMPS's warnings, one string)."""
    log = os.path.join(OUT, "warnings.log")
    lmp = new_lammps("-log", log if warnings else "none", "-screen", "none", "-nocite")
    cmds = [f"plugin load {plugin or plugin_build.plugin_path()}", f"units {units}", f"atom_style {style}",
            "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
            "create_atoms 1 single 0 0 0", f"create_atoms 1 single {2 * R + gap!r} 0 0"]
    if style.startswith("sphere"):
        cmds += [f"set type 1 diameter {2 * R!r}", f"set type 1 density {MAT.rho!r}", f"set atom 1 vx {speed!r}"]
    else:
        cmds += ["mass 1 1.0"]
    cmds += [f"timestep {dt!r}", "fix 1 all nve/sphere" if style.startswith("sphere") else "fix 1 all nve",
             "neighbor 0.0003 bin"] + (["comm_modify vel yes"] if vel else [])
    forces = [pair, f"pair_coeff * * {table}"]
    walls = [f"fix w all dem/contact/wall {wall}"] if wall else []
    cmds += (walls + forces if wall_first else forces + walls) + list(extra) + [f"run {steps}"]
    try:
        for c in cmds:
            lmp.command(c)
        if warnings:
            lmp.close()
            with open(log) as f:
                return " ".join(line.strip() for line in f if line.startswith("WARNING"))
        return None
    except Exception as e:       # (LAMMPS's error, raised by the lammps module)
        return str(e).splitlines()[0]
    finally:
        lmp.close()


def main():
    plugin_build.build()
    old = os.path.join(OUT, "oldplugin.so")
    subprocess.run(plugin_build._command("1 Jan 2020") + [old], check=True)
    corrupt = os.path.join(OUT, "corrupt.json")
    with open(corrupt, "w") as f:
        f.write('{"format": "dem_contact pair table", "version": ')
    cases = dict(
        runs=scene(good_table()),
        missing=scene(os.path.join(OUT, "nowhere.json")),
        corrupt=scene(corrupt),
        other_version=scene(edited("old.json", lambda d: d.update(version="0.0.1"))),
        unknown_law=scene(edited("law.json", lambda d: d["laws"][0].update(tangential="glue"))),
        bad_params=scene(edited("rows.json", lambda d: d.update(params=[[1.0, 2.0]]))),
        atomic=scene(good_table(), style="atomic"),
        no_vmax=scene(good_table(), pair="pair_style dem/contact"),
        bad_keyword=scene(good_table(), pair="pair_style dem/contact vmax 1.0 colour red"),
        long_step=scene(good_table(), dt=1e-4),
        no_ghost_velocity=scene(good_table(), vel=False),
        units=scene(good_table(), units="metal"),
        other_lammps=scene(good_table(), plugin=old),
        fast=scene(good_table(), gap=5e-4, speed=200.0, dt=5e-6, pair="pair_style dem/contact vmax 0.05"),
    )
    walled = good_table("walls.json", walls=[Wall(MAT)])
    plane = "plane -0.0009 0 0 1 0 0"
    cases.update(
        wall_runs=scene(walled, wall=plane),
        wall_kind=scene(walled, wall="sphere 0 0 0 0.001"),
        wall_numbers=scene(walled, wall="plane 0 0 x 1 0 0"),
        wall_before_pair=scene(walled, wall=plane, wall_first=True),
        wall_not_in_table=scene(good_table(), wall=plane),
        wall_index=scene(walled, wall=plane + " wall 3"),
        wall_curvature=scene(walled, wall="cylinder 0 0 0 0 0 1 0.005 in"),
        wall_behind=scene(walled, wall="plane 0.0001 0 0 1 0 0"),
        wall_stl=scene(walled, wall=f"mesh {os.path.join(OUT, 'nowhere.stl')}"),
        deep=scene(walled, gap=-5e-4, wall="plane -0.0005 0 0 1 0 0", warnings=True),
        changed_energy=scene(good_table(), extra=["run 5", "pair_style dem/contact vmax 1.0 energy yes",
                                                  f"pair_coeff * * {good_table()}"]),
        anew_after_none=scene(good_table(), extra=["run 5", "pair_style none",
                                                   "pair_style dem/contact vmax 1.0 energy yes",
                                                   f"pair_coeff * * {good_table()}"]),
        work_without_energy=scene(good_table(), extra=["compute c all dem/contact/local work"]),
        energy_without_energy=scene(good_table(), extra=["thermo_style custom step f_DEM_CONTACT_HISTORY"]),
        # (a periodic box 2.05 diameters wide: atom 1 touches atom 2 and has its other image in its neighbour
        # list, apart; the second run reads the contact back from the atoms' rows)
        narrow_box=scene(good_table(), extra=[f"change_box all x final {-2.05 * R!r} {2.05 * R!r} units box",
                                              "run 5"]),
        # (a third sphere touching atom 1 on the other side: two contacts, one row)
        too_many=scene(good_table(), pair="pair_style dem/contact vmax 1.0 slots 1",
                       extra=[f"create_atoms 1 single {-2 * R + 2e-5!r} 0 0", f"set type 1 diameter {2 * R!r}",
                              f"set type 1 density {MAT.rho!r}"]),
        grown=scene(good_table(), style="sphere 1",
                    extra=["variable d equal 0.002+step*1e-5", "fix grow all adapt 1 atom diameter v_d"]),
        grown_rmax=scene(good_table(), style="sphere 1", pair="pair_style dem/contact vmax 1.0 rmax 0.0012",
                         extra=["variable d equal 0.002+step*1e-5", "fix grow all adapt 1 atom diameter v_d"]),
    )
    print(json.dumps(cases))


if __name__ == "__main__":
    main()
