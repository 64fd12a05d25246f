"""Uhlmann's measures from a run's particles.csv, in u_ref and t_ref (the definitions of
xper_validation::fluid::published::dkt_measures): peak fall speed of the trailing disk (body 0)
before the collision and its time, peak fall speed of the leading disk (body 1) and its time,
the collision (centres within 1.01 d) and the time the trailing disk passes below the leading.

    python3 scenes/uhlmann_tumbling/measures.py OUT/particles.csv
"""
import csv
import math
import sys

D = 2.5e-3
U_REF = math.sqrt(math.pi * D / 2 * 0.5 * 9.81)
T_REF = D / U_REF


def main(path):
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            rows.setdefault(int(r["step"]), {})[int(r["body"])] = r
    trailing, leading = (0.0, 0.0), (0.0, 0.0)
    kiss = swap = float("nan")
    for step in sorted(rows):
        b = rows[step]
        if 0 not in b or 1 not in b:
            continue
        t = float(b[0]["time"]) / T_REF
        v = [-float(b[k]["vy"]) / U_REF for k in (0, 1)]
        if math.isnan(kiss) and v[0] > trailing[0]:
            trailing = (v[0], t)
        if v[1] > leading[0]:
            leading = (v[1], t)
        x = [(float(b[k]["x"]), float(b[k]["y"])) for k in (0, 1)]
        gap = math.hypot(x[0][0] - x[1][0], x[0][1] - x[1][1])
        if math.isnan(kiss) and gap < 1.01 * D:
            kiss = t
        if math.isnan(swap) and x[0][1] < x[1][1]:
            swap = t
    print(f"trailing peak {trailing[0]:.3f} u_ref at {trailing[1]:.2f} t_ref")
    print(f"leading peak {leading[0]:.3f} u_ref at {leading[1]:.2f} t_ref")
    print(f"collision {kiss:.2f} t_ref, swap {swap:.2f} t_ref")


if __name__ == "__main__":
    main(sys.argv[1])
