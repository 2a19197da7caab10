#!/usr/bin/env python3
"""Population diversity over generations, read offline from a run folder's checkpoints.

For every checkpoint in RUN/checkpoints (run with a large `keep_checkpoints` to keep them all)
prints: generation, mean and best fitness of that generation, the mean per-gene standard
deviation of the population, the mean pairwise Euclidean distance between genomes, the mean
|gene| (the weight scale), and how many distinct genomes there are. Used in docs/search.md.

Usage: python3 scripts/research/population-diversity.py RUN [--reference genomes/braitenberg-forager.json]
With --reference, also prints the mean distance from the population to that genome.
"""
import json
import math
import os
import sys


def main():
    args = sys.argv[1:]
    reference = None
    if "--reference" in args:
        i = args.index("--reference")
        reference = json.load(open(args[i + 1]))["parameters"]
        del args[i:i + 2]
    run = args[0]
    cdir = os.path.join(run, "checkpoints")
    header = "generation,mean,best,gene_std,pairwise,mean_abs,distinct"
    if reference:
        header += ",to_reference"
    print(header)
    for name in sorted(os.listdir(cdir)):
        if not name.endswith(".json"):
            continue
        d = json.load(open(os.path.join(cdir, name)))["payload"]
        inds = d["last"]["individuals"]
        genomes = [i["genome"]["parameters"] for i in inds]
        fit = [i["evaluation"]["fitness"] for i in inds if i["evaluation"]["fitness"] is not None]
        n, k = len(genomes), len(genomes[0])
        means = [sum(g[j] for g in genomes) / n for j in range(k)]
        std = sum(math.sqrt(sum((g[j] - means[j]) ** 2 for g in genomes) / n) for j in range(k)) / k
        pair, count = 0.0, 0
        for a in range(n):
            for b in range(a + 1, n):
                pair += math.dist(genomes[a], genomes[b])
                count += 1
        mean_abs = sum(abs(x) for g in genomes for x in g) / (n * k)
        distinct = len({tuple(g) for g in genomes})
        row = [d["last"]["generation"], sum(fit) / len(fit), max(fit), std, pair / count,
               mean_abs, distinct]
        if reference:
            row.append(sum(math.dist(g, reference) for g in genomes) / n)
        print(",".join(f"{x:.4g}" if isinstance(x, float) else str(x) for x in row))


main()
