"""A parameter study: a disk launched sliding on a floor, for several friction coefficients.

Friction slows the slip until the disk rolls; for a disk (I = m r^2 / 2) launched at v0
without spin, rolling starts at t* = v0 / (3 mu g) with speed 2 v0 / 3, whatever mu.
Each run is a scene built in Python; the study compares the measured t* with the formula
and plots both (matplotlib).

Run: python parameter_study.py [--out DIR] [--plot FILE]
"""

import argparse
import os

import numpy as np
import xper

G = 9.81     # m/s^2
V0 = 1.0     # m/s
R = 0.05     # m
DT = 1e-3    # s


def scene(mu):
    s = xper.Scene(name=f"rolling_mu_{mu:g}", dt=DT, duration=1.0, gravity=[0.0, -G])
    s.section("solver", tolerance=1e-10)
    s.section("output", frame_every=100)
    s.add("materials", name="steel", density=7800.0)
    s.add("laws", between=["disk", "floor"], kind="signorini_coulomb", friction=mu)
    s.add("bodies", shape="disk", center=[0.0, R], radius=R, material="steel", group="disk",
          velocity=[V0, 0.0])
    s.add("walls", from_=[-1.0, 0.0], to=[2.0, 0.0], group="floor")
    return s


def rolling_start(mu, out):
    """The time at which the disk's slip velocity v + w r vanishes, and its speed then."""
    sim = xper.Simulation.from_scene(scene(mu), out=out)
    while not sim.is_finished:
        sim.step()
        v = sim.bodies.velocity[0, 0]
        w = sim.bodies.angular_velocity[0, 0]
        if abs(v + w * R) < 1e-9:
            t, speed = sim.time, v
            sim.finish()
            return t, speed
    raise RuntimeError(f"mu = {mu}: still sliding at t = {sim.time} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/parameter_study")
    ap.add_argument("--plot", help="write t* against mu to this PNG")
    a = ap.parse_args()
    mus = [0.1, 0.2, 0.3, 0.5, 0.8]
    rows = []
    for mu in mus:
        t, v = rolling_start(mu, os.path.join(a.out, f"mu_{mu:g}"))
        exact = V0 / (3 * mu * G)
        rows.append((mu, t, exact, v))
        print(f"mu = {mu:4.2f}: rolls from t = {t:.4f} s (formula {exact:.4f} s, within one "
              f"step: {abs(t - exact) <= DT}), speed {v:.6f} m/s (formula {2 * V0 / 3:.6f})")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        mu, t, exact, _ = np.array(rows).T
        fig, ax = plt.subplots(figsize=(5, 3.5))
        grid = np.linspace(min(mus), max(mus), 100)
        ax.plot(grid, V0 / (3 * grid * G), label="v0 / (3 mu g)")
        ax.plot(mu, t, "o", label="xper")
        ax.set_xlabel("friction coefficient mu")
        ax.set_ylabel("time to rolling t* (s)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)


if __name__ == "__main__":
    main()
