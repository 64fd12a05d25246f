"""The contact network of a deposit read into NumPy: coordination, the granular stress
tensor, the distribution of normal forces, and the weight carried by the floor.

A bed of disks settles under gravity in a box (frictional, mu = 0.3). At the end:

* coordination number z = 2 N_gg / N_g over grain-grain contacts (each joins two grains);
* granular stress sigma = (1/A) sum_c f_c (x) l_c over grain-grain contacts, with l_c the
  branch vector between the centres and A the area the grains span (Christoffersen, Mehrabadi
  and Nemat-Nasser 1981; Pa, forces per m of thickness);
* normal forces over their mean, binned (their distribution, Radjai et al. 1996);
* the walls' vertical force against the grains' weight: at rest they are equal, which
  checks the contacts' impulses, normals, tangents and body pairs against an independent
  number (the floor alone carries a little more or less: friction on the sides holds part of
  the weight, or pulls down, depending on how the bed settled).

Run: python contact_network.py [--out DIR] [--grains N]
"""

import argparse

import numpy as np
import xper

G = 9.81      # m/s^2
DT = 2e-4     # s


def deposit(grains):
    s = xper.Scene(name="deposit", dt=DT, duration=0.5, alert_distance=5e-4,
                   gravity=[0.0, -G])
    s.section("output", frame_every=250, checkpoint_every=2500)
    s.add("materials", name="glass", density=2500.0)
    for a, b in [("grains", "grains"), ("grains", "floor"), ("grains", "sides")]:
        s.add("laws", between=[a, b], kind="signorini_coulomb", friction=0.3)
    s.add("generators", kind="box_of_disks", count=grains, radius=[0.002, 0.003],
          box=[[0.0, 0.0], [0.09, 0.1]], placement="random", seed=11, material="glass",
          group="grains")
    s.add("walls", from_=[0.0, 0.0], to=[0.09, 0.0], group="floor")
    s.add("walls", from_=[0.09, 0.0], to=[0.09, 0.2], group="sides")
    s.add("walls", from_=[0.0, 0.2], to=[0.0, 0.0], group="sides")
    return s


def network(sim):
    """The measures of the module's docstring, as a dict."""
    group = sim.bodies.group
    names = sim.group_names
    is_grain = group == names.index("grains")
    pairs = sim.contacts.bodies
    rn = sim.contacts.normal_impulse / DT                  # N/m
    force = sim.contacts.impulse / DT                      # on the second body, N/m
    between_grains = is_grain[pairs[:, 0]] & is_grain[pairs[:, 1]]
    active = rn > 0
    x = sim.bodies.position
    branch = x[pairs[:, 1]] - x[pairs[:, 0]]
    gg = between_grains & active
    r = sim.bodies.radius[is_grain]
    lo = (x[is_grain] - r[:, None]).min(axis=0)
    hi = (x[is_grain] + r[:, None]).max(axis=0)
    area = np.prod(hi - lo)
    sigma = np.einsum("ci,cj->ij", force[gg], branch[gg]) / area
    def wall_force(names_of_walls):
        """The force of the walls of these groups on the grains: + the force on the second
        body when the wall is the first, - when it is the second."""
        walls = [names.index(w) for w in names_of_walls]
        first = np.isin(group[pairs[:, 0]], walls)
        second = np.isin(group[pairs[:, 1]], walls)
        sign = np.where(first, 1.0, np.where(second, -1.0, 0.0))
        return (sign[:, None] * force).sum(axis=0)
    weight = sim.bodies.mass[is_grain].sum() * G
    mean = rn[gg].mean()
    counts, edges = np.histogram(rn[gg] / mean, bins=[0, 0.5, 1, 1.5, 2, 3, 5, np.inf])
    return {
        "z": 2 * gg.sum() / is_grain.sum(),
        "sigma": sigma,
        "floor_force": wall_force(["floor"]),
        "wall_force": wall_force(["floor", "sides"]),
        "weight": weight,
        "force_bins": (edges, counts),
        "kinetic_energy": sim.report["kinetic_energy"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/contact_network")
    ap.add_argument("--grains", type=int, default=200)
    a = ap.parse_args()
    sim = xper.Simulation.from_scene(deposit(a.grains), out=a.out)
    sim.run()
    m = network(sim)
    s = m["sigma"]
    print(f"coordination z = {m['z']:.3f}; kinetic energy {m['kinetic_energy']:.3e} J/m")
    print(f"granular stress (Pa): xx {s[0, 0]:.1f}, yy {s[1, 1]:.1f}, xy {s[0, 1]:.2f}, "
          f"yx {s[1, 0]:.2f}")
    w = m["weight"]
    print(f"grains' weight {w:.6g} N/m; vertical force of the floor {m['floor_force'][1]:.6g}"
          f" N/m, of the floor and the sides {m['wall_force'][1]:.6g} N/m (ratio "
          f"{m['wall_force'][1] / w:.6f})")
    edges, counts = m["force_bins"]
    print("normal force / mean:  " + "  ".join(
        f"[{lo:g}, {hi:g}): {c}" for lo, hi, c in zip(edges[:-1], edges[1:], counts)))


if __name__ == "__main__":
    main()
