#!/usr/bin/env python3
"""CPU ms of the AO chain (the passes of group "ao" in `render --stats`, measured on a second frame) for
vbao with and without the surface normals and the guard band, against the lesson's chain, at 1920x1080
on the demo scene. Rounds are interleaved so that load changes hit every setting alike; the median of
each setting is printed with its ratio to sao-lesson. Run from the repository root after
`cargo build --release`."""
import json, statistics, subprocess, sys

SETTINGS = {
    "sao-lesson": ["--method", "sao-lesson"],
    "vbao low, depth normals, no band": ["--method", "vbao", "--quality", "low", "--normals", "depth", "--guard-band", "0"],
    "vbao low, geometric normals, no band": ["--method", "vbao", "--quality", "low", "--normals", "geometric", "--guard-band", "0"],
    "vbao low, backface, geometric normals, auto band": ["--method", "vbao", "--quality", "low", "--thickness", "backface", "--guard-band", "auto"],
    "vbao high, depth normals, no band": ["--method", "vbao", "--quality", "high", "--normals", "depth", "--guard-band", "0"],
    "vbao high, geometric normals, no band": ["--method", "vbao", "--quality", "high", "--normals", "geometric", "--guard-band", "0"],
    "vbao high, geometric normals, auto band": ["--method", "vbao", "--quality", "high", "--guard-band", "auto"],
    "vbao high, backface, geometric normals, auto band": ["--method", "vbao", "--quality", "high", "--thickness", "backface", "--guard-band", "auto"],
}
ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 else 3
cpu = {k: [] for k in SETTINGS}
for _ in range(ROUNDS):
    for name, flags in SETTINGS.items():
        out = subprocess.run(
            ["./target/release/opengl3d", "render", "--scene", "Res/scenes/demo.toml", "--width", "1920",
             "--height", "1080", "--stats", "--out", "/tmp/timing.png", *flags],
            check=True, capture_output=True, text=True).stdout
        stats = json.loads(out[out.index("{"):out.rindex("}") + 1])
        cpu[name].append(sum(p["cpu_ms"] for p in stats["passes"] if p["group"] == "ao"))
base = statistics.median(cpu["sao-lesson"])
print("| setting | AO chain CPU ms (median of %d) | ratio to sao-lesson |" % ROUNDS)
print("|---|---:|---:|")
for name, v in cpu.items():
    m = statistics.median(v)
    print(f"| {name} | {m:.0f} | {m / base:.2f}× |")
