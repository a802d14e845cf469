"""What one group costs the answer key: seconds of work and bytes of each output format.

The cap :data:`pendulab.jobs.key.MAX_GROUPS` rests on these numbers. Groups of three student
numbers (a class's usual size), the common answers computed once beforehand (they do not
grow with the class); ``N`` groups timed (CPU time of this process, best of 3), then
rendered as CSV, JSON and PDF. Printed: per group, and for MAX_GROUPS groups.

Run: ``.venv/bin/python benchmarks/key_cost.py [--groups 40]``
"""
from __future__ import annotations

import argparse
import time

from pendulab.jobs import key
from pendulab.report.key import render


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--groups", type=int, default=40)
    args = ap.parse_args()
    n = args.groups
    groups = [(100_000 + 7919 * i, 200_000 + 104_729 * i % 99_991, 300_000 + i) for i in range(n)]
    key.answer_key(groups[:2])  # kernels compiled (or loaded) and the common answers warmed
    best = float("inf")
    for _ in range(3):
        t = time.process_time()
        k = key.answer_key(groups)
        best = min(best, time.process_time() - t)
    one = key.answer_key(groups[:1])
    common = time.process_time()
    key.common_answers()
    common = time.process_time() - common
    per = (best - common) / (n - 1)  # the common part once, each group after it
    print(f"{n} groups: {best:.2f} s CPU (the common answers {common:.2f} s of it); "
          f"{per * 1e3:.1f} ms per group")
    print(f"{key.MAX_GROUPS} groups (MAX_GROUPS): about {common + per * key.MAX_GROUPS:.0f} s")
    for fmt in ("csv", "json", "pdf"):
        size_n, size_1 = len(render(k, fmt)), len(render(one, fmt))
        per_b = (size_n - size_1) / (n - 1)
        print(f"{fmt:4}: {per_b / 1e3:.1f} kB per group; {key.MAX_GROUPS} groups about "
              f"{(size_1 + per_b * (key.MAX_GROUPS - 1)) / 1e6:.1f} MB")


if __name__ == "__main__":
    main()
