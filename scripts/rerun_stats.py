"""What to expect when a benchmark is run twice: the rerun check of scripts/bench_report.py and
scripts/bench_interior.sh.

Each run summarises a row by the median and the range (min..max) of k independent values (k
processes, or k sweeps over the same camera poses). Two runs of one build "agree" on a row when each
run's median lies inside the other's range. Even when both runs draw their values from one and the
same distribution, that does not always happen: for k = 5 it happens for only 72 % of the rows, for
k = 9 for 94 %. For odd k the chance depends only on the ranks of the 2k values, so it is the same
for every continuous distribution; agreement_probability() counts it exactly over the C(ka + kb, ka)
equally likely orderings. A pair of runs then reproduces when its count of agreeing rows is in the
range a binomial count with that probability gives (rows treated as independent).

Usage as a script: python3 scripts/rerun_stats.py [k ...] prints the probabilities; --self-test
checks them (ctest bench.rerun_stats).
"""
import functools
import itertools
import math
import random
import statistics
import sys


def _median_rank(ranks):
    return ranks[len(ranks) // 2]


@functools.lru_cache(maxsize=None)
def agreement_probability(ka, kb):
    """(both, a_in_b, b_in_a) for runs of ka and kb values drawn from one continuous distribution:
    the chance that each median lies inside the other run's range, that run A's median lies inside
    B's range, and that B's lies inside A's. Exact when ka and kb are odd (ranks only); otherwise
    estimated from 200,000 simulated pairs of normal draws (the median of an even count is the mean
    of the middle two, so the chance then depends a little on the distribution)."""
    if ka < 1 or kb < 1:
        return (0.0, 0.0, 0.0)
    if ka % 2 == 1 and kb % 2 == 1:
        n = ka + kb
        both = a_in_b = b_in_a = total = 0
        for pos in itertools.combinations(range(n), ka):
            chosen = set(pos)
            a = list(pos)
            b = [i for i in range(n) if i not in chosen]
            ma, mb = _median_rank(a), _median_rank(b)
            x = b[0] < ma < b[-1]
            y = a[0] < mb < a[-1]
            a_in_b += x
            b_in_a += y
            both += x and y
            total += 1
        return (both / total, a_in_b / total, b_in_a / total)
    rng = random.Random(12345)
    trials = 200000
    both = a_in_b = b_in_a = 0
    for _ in range(trials):
        a = [rng.gauss(0.0, 1.0) for _ in range(ka)]
        b = [rng.gauss(0.0, 1.0) for _ in range(kb)]
        x = min(b) <= statistics.median(a) <= max(b)
        y = min(a) <= statistics.median(b) <= max(a)
        a_in_b += x
        b_in_a += y
        both += x and y
    return (both / trials, a_in_b / trials, b_in_a / trials)


def binomial_band(n, p, mass=0.95):
    """(lo, hi): the central `mass` of a binomial(n, p) count (each tail at most (1 - mass) / 2)."""
    tail = (1.0 - mass) / 2.0
    pmf = [math.comb(n, i) * p ** i * (1.0 - p) ** (n - i) for i in range(n + 1)]
    lo, acc = 0, 0.0
    for i in range(n + 1):
        if acc + pmf[i] > tail:
            lo = i
            break
        acc += pmf[i]
    hi, acc = n, 0.0
    for i in range(n, -1, -1):
        if acc + pmf[i] > tail:
            hi = i
            break
        acc += pmf[i]
    return lo, hi


def expectation_text(n_rows, n_agree, ka, kb, what="rows"):
    """One sentence comparing n_agree of n_rows with what two runs of one distribution give."""
    p = agreement_probability(ka, kb)[0]
    lo, hi = binomial_band(n_rows, p)
    exact = "exactly, for any distribution" if ka % 2 == 1 and kb % 2 == 1 else "by simulation with normal draws"
    verdict = ("inside that band: the two runs differ no more than repeated draws from one distribution do"
               if lo <= n_agree <= hi else
               ("below that band: the runs differ by more than their ranges allow" if n_agree < lo else
                "above that band"))
    return ("With %d and %d values per %s the chance that a %s agrees this way is %.1f %% (%s), so %.1f of %d "
            "are expected (95 %% of pairs of runs: %d to %d); %d is %s." % (
                ka, kb, what.rstrip("s"), what.rstrip("s"), 100.0 * p, exact, p * n_rows, n_rows, lo, hi,
                n_agree, verdict))


def self_test():
    """Checks the exact counts against independent arithmetic and against simulated runs drawn from
    two unlike distributions (a skewed and a two-mode one); returns the number of failures."""
    failures = 0

    def check(what, ok):
        nonlocal failures
        print("%s %s" % ("ok  " if ok else "FAIL", what))
        failures += 0 if ok else 1

    # k = 1: one value each, never strictly inside a one-point range. k = 3, counted by hand: A's
    # median is the m-th of the 6 values in (m-1)(6-m) of the 20 orderings, and lies inside B's range
    # for m = 3, 4: 12 of 20 (3/5). Both ways: 8 of 20 (2/5).
    check("k=1 gives 0", agreement_probability(1, 1) == (0.0, 0.0, 0.0))
    both3, one3, other3 = agreement_probability(3, 3)
    check("k=3: one way 3/5, both ways 2/5", abs(one3 - 0.6) < 1e-12 and abs(other3 - 0.6) < 1e-12
          and abs(both3 - 0.4) < 1e-12)
    rng = random.Random(20261128)
    draws = {
        "lognormal": lambda: rng.lognormvariate(0.0, 1.5),
        "two modes": lambda: rng.gauss(0.0, 0.1) + (5.0 if rng.random() < 0.2 else 0.0),
    }
    trials = 40000
    for k in (5, 9):
        both = agreement_probability(k, k)[0]
        for name, draw in draws.items():
            hit = 0
            for _ in range(trials):
                a = [draw() for _ in range(k)]
                b = [draw() for _ in range(k)]
                hit += (min(b) <= statistics.median(a) <= max(b)) and (min(a) <= statistics.median(b) <= max(a))
            sigma = math.sqrt(both * (1.0 - both) / trials)
            check("k=%d, %s: simulated %.4f against exact %.4f (within 5 sigma = %.4f)" % (
                k, name, hit / trials, both, 5 * sigma), abs(hit / trials - both) <= 5 * sigma)
    lo, hi = binomial_band(100, 0.5)
    check("binomial band of 100 fair coins is 40..60", (lo, hi) == (40, 60))
    return failures


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(1 if self_test() else 0)
    for k in [int(a) for a in sys.argv[1:]] or [3, 5, 6, 7, 9, 11]:
        both, ab, ba = agreement_probability(k, k)
        print("k=%d: both ways %.4f, one way %.4f" % (k, both, ab))
