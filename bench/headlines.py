#!/usr/bin/python3
"""The table `make bench` ends with: every headline row the benchmarks
appended to FILE (benchlib.headline), in the order they ran, and how many
targets hold.

    /usr/bin/python3 bench/headlines.py FILE
"""
import json
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bench/headlines.py FILE")
    with open(sys.argv[1]) as f:
        rows = [json.loads(line) for line in f if line.strip()]
    print("\n## Headline figures (each measured side by side in this run)\n")
    print("| what | measured | target | holds | bench |")
    print("|---|---|---|:---:|---|")
    for r in rows:
        print("| %s | %s | %s | %s | %s |" % (r["what"], r["measured"], r["target"], "yes" if r["holds"] else "no",
                                            r["bench"]))
    print("\n%d of %d targets hold" % (sum(r["holds"] for r in rows), len(rows)))


if __name__ == "__main__":
    main()
