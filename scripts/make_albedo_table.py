#!/usr/bin/env python3
"""Builds data/halfspace_albedo.txt: the exact diffuse reflectance of a
half-space at normal incidence (the `albedo` of a translucent material) over
the reduced single-scattering albedo, for a grid of boundary indices eta and
Henyey-Greenstein mean cosines g, each value with its standard error, from
`subsurf halfspace`. The format is described in docs/albedo.md.

    python3 scripts/make_albedo_table.py build/subsurf data/halfspace_albedo.txt [PATHS]

Each grid point is one run of the exact Monte Carlo reference with sigma_t = 1,
sigma_s = alpha, sigma_a = 1 - alpha, where alpha is the single-scattering
albedo whose reduced albedo alpha' = (1 - g) alpha / (1 - g alpha) sits on the
grid u = sqrt(1 - alpha'). The ends are exact and not simulated: u = 1
(alpha = 0) reflects nothing, u = 0 (no absorption) returns every photon that
entered, 1 - F(0). Seeds are fixed, so the table is reproducible bit for bit.
"""
import json
import subprocess
import sys
import time
import zlib

ETAS = [1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6]
GS = [0.0, 0.3, 0.6, 0.8, 0.9]
US = [0.0, 0.02, 0.04, 0.07, 0.1, 0.14, 0.19, 0.25, 0.32, 0.4, 0.48, 0.57, 0.66, 0.76,
      0.86, 0.94, 1.0]
VERSION = 1


def fresnel0(eta):
    return ((eta - 1.0) / (eta + 1.0)) ** 2


def run(binary, eta, g, u, paths, seed):
    ap = 1.0 - u * u
    alpha = ap / (1.0 - g + g * ap)
    cmd = ["nice", binary, "halfspace", "--sigma-s", repr(alpha), "--sigma-a",
           repr(1.0 - alpha), "--g", repr(g), "--phase", "hg", "--eta", repr(eta),
           "--paths", str(paths), "--seed", str(seed), "--rbins", "2", "--xbins", "1",
           "--ybins", "1", "--threads", "2", "--quiet", "--json", "-"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    r = json.loads(out)["reflectance"]
    return r["value"], r["stderr"]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    binary, path = sys.argv[1], sys.argv[2]
    paths = int(float(sys.argv[3])) if len(sys.argv) == 4 else 150000
    start = time.time()
    lines = [
        "# subsurf half-space albedo table: exact diffuse reflectance at normal incidence",
        "# per unit incident power (specular excluded) of a half-space of reduced albedo",
        "# alpha' = 1 - u^2 behind a smooth boundary eta, HG phase g; built by",
        "# scripts/make_albedo_table.py with %d paths per point (format: docs/albedo.md)." % paths,
        "subsurf-albedo-table %d" % VERSION,
        "eta %d %s" % (len(ETAS), " ".join(repr(e) for e in ETAS)),
        "g %d %s" % (len(GS), " ".join(repr(g) for g in GS)),
        "u %d %s" % (len(US), " ".join(repr(u) for u in US)),
    ]
    seed = 1
    for eta in ETAS:
        for g in GS:
            vals, errs = [], []
            for u in US:
                if u == 0.0:
                    v, e = 1.0 - fresnel0(eta), 0.0
                elif u == 1.0:
                    v, e = 0.0, 0.0
                else:
                    v, e = run(binary, eta, g, u, paths, seed)
                seed += 1
                vals.append(v)
                errs.append(e)
            for a, b in zip(vals, vals[1:]):
                if not b < a:
                    sys.exit("eta %g g %g: not decreasing in u (%r then %r): raise PATHS"
                             % (eta, g, a, b))
            lines.append("curve %r %r %s %s" % (eta, g, " ".join("%.6f" % v for v in vals),
                                                 " ".join("%.6f" % e for e in errs)))
            print("eta %g g %g done (%.0f s)" % (eta, g, time.time() - start), flush=True)
    text = "\n".join(lines) + "\n"
    crc = zlib.crc32(text.encode("ascii")) & 0xFFFFFFFF
    text += "crc32 %08x\n" % crc
    with open(path, "w") as f:
        f.write(text)
    print("wrote %s in %.0f s" % (path, time.time() - start))


if __name__ == "__main__":
    main()
