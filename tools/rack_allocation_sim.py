"""Issue #33: attempts to the reachable can's first valid sample under allocation rules, simulated from the outcome
rates tools/rack_outcomes.py measured (each attempt an independent draw of its region's outcome). Rules: rr (round robin
with the give-up rules), deferD_S (regions with no valid sample, >= 10 attempts and at most S of them past the screen
take one turn in D), stride, ucbC, ts (Thompson). ORACLE=behind,caged closes those kinds for free (a bound).
Usage: python3 tools/rack_allocation_sim.py OUT.json[,...] rr,defer8_0 SEEDS"""
import json, sys, heapq, math
import numpy as np
R = ["out of reach", "hand in collision", "ik failed", "in collision", "outside limits", "valid"]
def load(f):
    d = json.load(open(f)); P = []
    for x in d:
        c = np.array([x["failures"].get(r, 0) for r in R[:-1]] + [x["valid"]], float); P.append(c / c.sum())
    return d, np.array(P)
def stage(cnt):  # cnt: per-region counts [oor, hic, ikf, inc, lim, valid]
    n = cnt.sum(1); s = n - cnt[:, 0] - cnt[:, 1]; v = s - cnt[:, 2]; f = cnt[:, 5]
    return (s + 1) / (n + 2) * (v + 1) / (s + 2) * (f + 1) / (v - cnt[:, 4] + 2)
def hopeless_open(cnt, give_up=50):
    n = cnt.sum(1); f = cnt[:, 5]
    hope = (n >= 20) & (cnt[:, 0] >= 0.9 * n)
    budget = np.where(cnt[:, 3] > 0, give_up * 4, np.where(hope, n, give_up))
    return (f > 0) | (n < budget)
def run(P, kinds, rule, rng, cap=30000):
    m = len(P); cnt = np.zeros((m, 6)); pos = 0; passv = np.zeros(m); t = 0
    target = np.array([k == "reachable" for k in kinds])
    while t < cap:
        op = hopeless_open(cnt)
        if rule == "rr" or rule.startswith("defer"):
            while True:
                jj = pos % m; pos += 1
                if not op[jj]: continue
                if rule == "rr" and ORACLE and kinds[jj] in ORACLE: continue
                if rule.startswith("defer"):
                    D, SP = rule[5:].split("_"); D = int(D); SP = float(SP)
                    n = cnt[jj].sum(); passes = n - cnt[jj, 0] - cnt[jj, 1]
                    if cnt[jj, 5] == 0 and n >= 10 and passes <= SP * n and ((pos - 1) // m + jj) % D:
                        continue
                break
            j = jj
        elif rule.startswith("stride"):
            w = stage(cnt); cand = np.where(op)[0]; j = cand[np.argmin(passv[cand])]
        elif rule.startswith("ucb"):
            c = float(rule[3:]); n = cnt.sum(1); w = stage(cnt)
            sc = np.where(op, w + c * np.sqrt(np.log(t + 2) / (n + 1)), -1); j = int(np.argmax(sc))
        elif rule == "ts":
            n = cnt.sum(1); s = n - cnt[:, 0] - cnt[:, 1]; v = s - cnt[:, 2]; f = cnt[:, 5]
            th = rng.beta(s + 1, n - s + 1) * rng.beta(v + 1, s - v + 1) * rng.beta(f + 1, v - f + 1)
            j = int(np.argmax(np.where(op, th, -1)))
        o = rng.choice(6, p=P[j]); cnt[j, o] += 1; t += 1
        if rule.startswith("stride"): passv[j] += 1.0 / stage(cnt[j:j+1])[0]
        if o == 5 and target[j]: return t
    return cap
import os
ORACLE = os.environ.get('ORACLE', '').split(',') if os.environ.get('ORACLE') else ()
files = sys.argv[1].split(","); rules = sys.argv[2].split(",")
for f in files:
    d, P = load(f); kinds = [x["kind"] for x in d]
    for rule in rules:
        res = [run(P, kinds, rule, np.random.default_rng(s)) for s in range(int(sys.argv[3]))]
        print(f, rule, "median", np.median(res), "quartiles", np.percentile(res, [25, 75]).round(), flush=True)
