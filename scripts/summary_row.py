"""One row of the seed run tables (seed_static_runs.csv, seed_fine_runs.csv) from a run's
summary.json: python3 summary_row.py SUMMARY_JSON LABEL RANKS [PARTS_CSV].

With PARTS_CSV (written by run_in_parts.sh) the run was made in parts: the wall time is the sum
of the parts' wall seconds and the memory the largest part's (rows without a peak_rss_kib, parts
killed before /usr/bin/time could report, are skipped)."""
import csv
import json
import sys

s = json.load(open(sys.argv[1]))
wall = s["total_seconds"]
rss = max(s["peak_memory_bytes_per_rank"]) / 2**20
if len(sys.argv) > 4 and sys.argv[4]:
    parts = list(csv.DictReader(open(sys.argv[4])))
    wall = sum(float(p["wall_seconds"]) for p in parts if p["wall_seconds"])
    rss = max([rss] + [float(p["peak_rss_kib"]) / 1024 for p in parts if p["peak_rss_kib"]])
print(f'{sys.argv[2]},{sys.argv[3]},{wall:.0f},{rss:.0f},{s["newton_iterations"]},{s["steps"]},'
      f'{s["cutbacks"]},{s["interface_points"]},{s["interface_open"]},{s["interface_slipping"]},'
      f'{max(s["newton_per_step"])},{s.get("factorizations", 0)}')
