"""Study 6: domain truncation. Hc on the default box X in [-4.5, 1.5], Y in [-3, 3] b/a and on
boxes 2x and 4x larger at the SAME mesh size (129, 257, 513 points), so only the domain changes;
plus M = 1 (rigid-isoviscous regime), where the widened default domain of
``problem.default_domain`` is compared with boxes 2x and 4x larger again.

    python validation/point/domain.py
"""

from common import Store, solve_case
from tqdm import tqdm

from ehl_multigrid.point import default_domain, problem_from_moes

CASES = [(5.0, 0.0), (10.0, 0.0), (5.0, 10.0), (20.0, 10.0), (50.0, 2.5), (100.0, 10.0)]


def main() -> None:
    st = Store("domain.json")
    todo = [(M, L, f, n) for M, L in CASES for f, n in ((1, 129), (2, 257), (4, 513))]
    todo += [(1.0, 0.0, f, n) for f, n in ((1, 129), (2, 257), (4, 513))]
    for M, L, f, n in tqdm(todo, desc="domain"):
        key = f"{M}_{L}_{f}_{n}"
        if key in st:
            continue
        xmin, xmax, ymax = default_domain(problem_from_moes(M, L))
        if M >= 5.0:  # the classic fixed box X in [-4.5, 1.5], Y in [-3, 3], scaled
            xmin, xmax, ymax = -4.5, 1.5, 3.0
        row = solve_case(M, L, 1.0, "roelands", "dowson-higginson", n, xmin=xmin * f, xmax=xmax * f,
                         ymax=ymax * f, max_cycles=40)
        row.update(factor=f, xmin=xmin * f, xmax=xmax * f, ymax=ymax * f)
        st.put(key, row)
    print("| (M, L) | Hc box x1 | x2 | x4 | x2 / x1 - 1 | x4 / x1 - 1 |")
    print("|---|---|---|---|---|---|")
    for M, L in [*CASES, (1.0, 0.0)]:
        r = [st.data.get(f"{M}_{L}_{f}_{n}", {}) for f, n in ((1, 129), (2, 257), (4, 513))]
        hc = [x.get("Hc") if x.get("converged") else None for x in r]
        d = [f"{100 * (h / hc[0] - 1):+.2f} %" if h and hc[0] else "-" for h in hc[1:]]
        print(f"| ({M:g}, {L:g}) | " + " | ".join(f"{h:.4f}" if h else "-" for h in hc) + f" | {d[0]} | {d[1]} |")


if __name__ == "__main__":
    main()
