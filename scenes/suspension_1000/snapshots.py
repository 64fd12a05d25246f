"""Draws the grains of a run of this scene at the first and last rows of its particles.csv
into snapshots.png (standard library only): python3 snapshots.py OUT_DIR [PNG]."""
import csv
import struct
import sys
import zlib

BOX = (0.096, 0.192)  # m, the fluid domain
SCALE = 4000  # pixels per m


def frames(path):
    rows = list(csv.DictReader(open(path)))
    times = sorted({float(r["time"]) for r in rows})
    pick = [times[0], times[-1]]
    return [(t, [r for r in rows if float(r["time"]) == t]) for t in pick]


def draw(panels):
    w, h = int(BOX[0] * SCALE), int(BOX[1] * SCALE)
    gap = 20
    width = len(panels) * w + (len(panels) + 1) * gap
    height = h + 2 * gap
    img = [[(255, 255, 255)] * width for _ in range(height)]
    for k, (_, rows) in enumerate(panels):
        x0 = gap + k * (w + gap)
        for x in range(w):
            img[gap][x0 + x] = img[gap + h - 1][x0 + x] = (0, 0, 0)
        for y in range(h):
            img[gap + y][x0] = img[gap + y][x0 + w - 1] = (0, 0, 0)
        speeds = [abs(float(r["vy"])) for r in rows]
        top = max(speeds) or 1.0
        for r, s in zip(rows, speeds):
            cx, cy, rad = float(r["x"]) * SCALE, float(r["y"]) * SCALE, 0.001 * SCALE
            shade = int(200 * (1 - s / top))
            colour = (shade, shade, 255 - shade // 2)
            for py in range(int(cy - rad), int(cy + rad) + 1):
                for px in range(int(cx - rad), int(cx + rad) + 1):
                    if (px - cx) ** 2 + (py - cy) ** 2 <= rad * rad and 0 <= px < w and 0 <= py < h:
                        img[gap + h - 1 - py][x0 + px] = colour
    return width, height, img


def write_png(path, width, height, img):
    raw = b"".join(b"\x00" + bytes(c for p in row for c in p) for row in img)
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


if __name__ == "__main__":
    out = sys.argv[1]
    panels = frames(out + "/particles.csv")
    for t, rows in panels:
        print(f"t = {t:.4f} s: {len(rows)} grains")
    write_png(sys.argv[2] if len(sys.argv) > 2 else "snapshots.png", *draw(panels))
