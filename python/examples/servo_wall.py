"""A lid held at a constant pressure on a bed of disks, driven from Python.

The lid is a rigid plate (a rectangle) whose sideways motion and rotation are imposed (0)
and whose vertical force Python sets between steps: the pressure asked for times the lid's
length, plus the lid's weight, which gravity adds back. The pressure the grains exert on the
lid is measured independently, from the normal impulses of the lid's contacts:

    p = sum(r_n) / (h L)            (Pa; 2D: N per m of thickness over the lid's length L)

Run: python servo_wall.py [--out DIR] [--pressure PA] [--grains N] [--plot FILE]
"""

import argparse

import numpy as np
import xper

G = 9.81          # m/s^2
DT = 2e-4         # s
WIDTH = 0.09      # m, the box and the lid
RHO = 2500.0      # kg/m^3, glass


def build(grains):
    s = xper.Scene(name="servo_wall", dt=DT, duration=0.3, alert_distance=5e-4,
                   gravity=[0.0, -G])
    s.section("output", frame_every=100, checkpoint_every=1000)
    s.add("materials", name="glass", density=RHO)
    # No law between the lid and the walls: the lid moves only vertically and never
    # touches them.
    for a, b in [("grains", "grains"), ("grains", "walls"), ("grains", "lid")]:
        s.add("laws", between=[a, b], kind="signorini_coulomb", friction=0.3)
    s.add("generators", kind="box_of_disks", count=grains, radius=[0.002, 0.003],
          box=[[0.0, 0.0], [WIDTH, 0.1]], placement="random", seed=7, material="glass",
          group="grains")
    s.add("walls", from_=[0.0, 0.0], to=[WIDTH, 0.0], group="walls")
    s.add("walls", from_=[WIDTH, 0.0], to=[WIDTH, 0.2], group="walls")
    s.add("walls", from_=[0.0, 0.2], to=[0.0, 0.0], group="walls")
    # The lid: 2 mm above the box, narrower than it by a gap of 0.5 mm on each side.
    s.add("bodies", shape="rectangle", center=[WIDTH / 2, 0.103], size=[WIDTH - 1e-3, 0.004],
          material="glass", group="lid",
          drive={"x": {"velocity": 0.0}, "rotation": {"velocity": 0.0}})
    return s


def lid_pressure(sim, lid):
    """Pressure of the grains on the lid from its contacts' normal impulses (Pa)."""
    pairs = sim.contacts.bodies
    on_lid = (pairs == lid).any(axis=1)
    return sim.contacts.normal_impulse[on_lid].sum() / (DT * (WIDTH - 1e-3))


def run(out, pressure=2000.0, grains=200, ramp=0.1):
    sim = xper.Simulation.from_scene(build(grains), out=out)
    lid = int(np.flatnonzero(sim.bodies.group == sim.group_names.index("lid"))[0])
    mass = sim.bodies.mass[lid]
    times, asked, measured = [], [], []

    def control(s):
        # The pressure asked rises linearly to `pressure` over `ramp` seconds, then holds.
        p = pressure * min(1.0, s.time / ramp)
        force = s.bodies.force.copy()
        # N per m of thickness: p L downwards in all, the lid's weight included.
        force[lid, 1] = -p * (WIDTH - 1e-3) + mass * G
        s.bodies.force = force
        times.append(s.time)
        asked.append(p)
        measured.append(lid_pressure(s, lid))

    control(sim)
    sim.run(callback=control)
    sim.finish()
    return np.array(times), np.array(asked), np.array(measured), mass


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/servo_wall")
    ap.add_argument("--pressure", type=float, default=2000.0, help="Pa")
    ap.add_argument("--grains", type=int, default=200)
    ap.add_argument("--plot", help="write the pressures against time to this PNG")
    a = ap.parse_args()
    t, asked, measured, mass = run(a.out, a.pressure, a.grains)
    last = t > 0.2
    error = np.abs(measured[last] - asked[last]).max() / a.pressure
    print(f"lid mass {mass:.4g} kg/m; pressure asked {a.pressure:g} Pa; measured over "
          f"t > 0.2 s: mean {measured[last].mean():.6g} Pa, largest error {100 * error:.3f} %")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot(t, asked, label="asked")
        ax.plot(t, measured, label="measured on the lid's contacts", lw=0.8)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("pressure (Pa)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)


if __name__ == "__main__":
    main()
