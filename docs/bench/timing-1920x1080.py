"""AO chain cost at 1920x1080: docs/bench/timing-1920x1080.md (run from the repository root after
`cargo build --release`; prints the markdown table)."""
import json, os, subprocess, statistics, sys, tempfile
configs = [
 ("sao-lesson n11", ["--method","sao-lesson"]),
 ("sao n4", ["--method","sao","--samples","4"]),
 ("sao n11", ["--method","sao"]),
 ("hemisphere n8", ["--method","hemisphere","--samples","8"]),
 ("hbao n8", ["--method","hbao","--samples","8"]),
 ("gtao high", ["--method","gtao","--quality","high"]),
 ("vbao low", ["--method","vbao","--quality","low"]),
 ("vbao medium", ["--method","vbao","--quality","medium"]),
 ("vbao high", ["--method","vbao","--quality","high"]),
 ("vbao low, backface", ["--method","vbao","--quality","low","--thickness","backface"]),
 ("vbao high, backface", ["--method","vbao","--quality","high","--thickness","backface"]),
 ("vbao low, full", ["--method","vbao","--quality","low","--ao-resolution","full"]),
]
rows=[]
for rep in range(5):
  for name, args in configs:
    out = subprocess.run(["./target/release/opengl3d","render","--width","1920","--height","1080","--stats","--out",os.path.join(tempfile.gettempdir(), "opengl3d-timing.png")]+args, capture_output=True, text=True).stdout
    passes = json.loads(out)["passes"]
    ao = [p for p in passes if p["group"]=="ao"]
    rows.append((name, sum(p["cpu_ms"] for p in ao), sum(p["ms"] for p in ao), {p["name"]: round(p["cpu_ms"],1) for p in ao}))
res={}
for name,_ in configs:
  cpu=[r[1] for r in rows if r[0]==name]; wall=[r[2] for r in rows if r[0]==name]
  detail=[r[3] for r in rows if r[0]==name][-1]
  res[name]=(statistics.median(cpu), statistics.median(wall), detail)
base=res["sao-lesson n11"][0]
print("| setting | AO chain CPU ms | ratio to sao-lesson | wall ms | passes (CPU ms, last run) |")
print("|---|---:|---:|---:|---|")
for name,(c,w,d) in res.items():
  print(f"| {name} | {c:.1f} | {c/base:.2f}× | {w:.1f} | {', '.join(f'{k} {v}' for k,v in d.items())} |")
