"""A scene stepped from Python and run by `xper run` give the same outputs byte for byte,
and a checkpoint written by either resumes in the other."""

import pytest
import xper
from conftest import cut_scene, run_cli, same_outputs

# 2D: one disk dropped on a wall (contact from step ~300); 2D: a bed of disks; 3D: spheres
# and polyhedra poured into a box; fracture: a bimaterial specimen pulled apart; fluid: a
# grain settling.
SCENES = [
    ("drop", {"duration": "0.35"}),
    ("newton_deposit", {"steps": "40", "dump_problems": "[]"}),
    ("mixed_shapes_3d", {"duration": "0.04"}),
    ("bimaterial_small", {"steps": "50"}),
    ("single_grain_settling", {"duration": "0.02"}),
]


@pytest.mark.parametrize("name,edits", SCENES)
def test_python_steps_give_the_cli_outputs(name, edits, tmp_path, fresh):
    scene = cut_scene(name, tmp_path, **edits)
    cli, py = fresh("cli"), fresh("py")
    run_cli("run", scene, "--out", cli, "--quiet")
    sim = xper.Simulation.from_file(scene, out=py)
    # Uneven chunks: how the steps are asked for must not matter.
    sim.step(7)
    sim.step()
    sim.run(until=sim.time + 10 * (sim.time / sim.step_index))
    sim.run()
    assert sim.is_complete and sim.is_finished
    assert sim.summary["status"] == "completed"
    same_outputs(cli, py)


@pytest.mark.parametrize("name,edits", SCENES[:1] + SCENES[2:])
def test_checkpoints_cross_between_python_and_cli(name, edits, tmp_path, fresh):
    scene = cut_scene(name, tmp_path, **edits)
    whole = fresh("whole")
    run_cli("run", scene, "--out", whole, "--quiet")
    stop = 13

    # Python stops, the command resumes.
    py_then_cli = fresh("py_cli")
    sim = xper.Simulation.from_file(scene, out=py_then_cli)
    sim.step(stop)
    assert sim.finish()["status"] == "stopped"
    run_cli("run", scene, "--out", py_then_cli, "--resume", "--quiet")
    same_outputs(whole, py_then_cli)

    # The command stops, Python resumes.
    cli_then_py = fresh("cli_py")
    run_cli("run", scene, "--out", cli_then_py, "--stop-at-step", stop, "--quiet")
    sim = xper.Simulation.from_file(scene, out=cli_then_py, resume=True)
    assert sim.step_index == stop
    sim.run()
    same_outputs(whole, cli_then_py)


def test_a_checkpoint_written_between_steps_resumes(tmp_path, fresh):
    scene = cut_scene("drop", tmp_path, duration="0.05")
    whole = fresh("whole")
    run_cli("run", scene, "--out", whole, "--quiet")
    out = fresh("py")
    sim = xper.Simulation.from_file(scene, out=out)
    sim.step(21)
    sim.write_checkpoint()
    del sim  # as if the interpreter had been killed here: no finish()
    sim = xper.Simulation.from_file(scene, out=out, resume=True)
    assert sim.step_index == 21
    sim.run()
    same_outputs(whole, out)


def test_save_and_load_without_the_scene_file(tmp_path, fresh):
    scene = cut_scene("mixed_shapes_3d", tmp_path, duration="0.03")
    whole = fresh("whole")
    run_cli("run", scene, "--out", whole, "--quiet")
    out = fresh("saved")
    sim = xper.Simulation.from_file(scene, out=out)
    sim.step(17)
    assert sim.save() == str(out)
    del sim
    scene.unlink()                      # the checkpoint keeps the scene's text
    sim = xper.Simulation.load(out)
    assert sim.step_index == 17 and sim.scene == str(out / "scene.toml")
    sim.run()
    same_outputs(whole, out)
