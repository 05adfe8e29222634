#!/usr/bin/env python3
"""Writes docs/consistency.md from the JSON of examples/consistency.

Usage: consistency_report.py SUITES_JSON FACTORS_JSON COMMAND RAISED_ACCEL [TUNING_JSON [MOTION_JSON]]
(MOTION_JSON holds the suites monocular-motion and, optionally, monocular-gauge)
           > docs/consistency.md

SUITES_JSON holds the suites planar, monocular and monocular-forests; FACTORS_JSON the
suite monocular-factors; TUNING_JSON monocular-tuning; MOTION_JSON monocular-motion; COMMAND
is the command that regenerates the page (printed on it).
Every number on the page comes from the two files; the sentences that judge a number
(inside or outside a bound, which factor matters) are computed from it too.
"""
import json
import math
import statistics
import sys

PIPELINES = [("first_sight", "width from the first sight (IDR)"),
             ("thesis", "width after XYZ-R (the thesis)"),
             ("none", "no width")]


def fmt(v, digits=2):
    if v is None:
        return "inf"
    if isinstance(v, float) and (math.isinf(v) or math.isnan(v)):
        return "inf"
    if abs(v) >= 1e5:
        return f"{v:.2e}"
    return f"{v:.{digits}f}"


def bounds(e):
    lo, hi = e["nees_bounds"]
    return f"[{lo:.2f}, {hi:.2f}]"


def planar_section(planar):
    out = []
    modes = [m for m in ("textbook", "first_estimates", "invariant", "iterated", "ideal") if m in planar]
    any_entry = planar[modes[0]]
    out.append(f"{any_entry['ensembles']} ensembles (seeds {any_entry['seeds'][0]}-{any_entry['seeds'][1]}) of "
               f"{any_entry['runs']} runs each; robot-pose NEES (3 dof) from the second step to the end of the "
               "second lap, the simulator's true noise given to the filter, known association.")
    out.append("")
    out.append("| mode | NEES mean | median run | 95% bounds (one ensemble) | fraction inside, smallest | "
               "by seed | position (2 dof) mean | heading (1 dof) mean | NIS mean (2 dof) | NIS above 95% gate | "
               "landmark RMS (m) |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|")
    for m in modes:
        e = planar[m]
        by_seed = ", ".join(f"{f:.2f}" for f in e["fraction_inside_by_seed"])
        nis = e["nis"]["range_bearing"]
        out.append(f"| {m} | {fmt(e['nees_mean'])} | {fmt(e['nees_median_run'])} | {bounds(e)} | "
                   f"{e['fraction_inside']:.3f} | {by_seed} | {fmt(e['parts']['position']['nees_mean'])} | "
                   f"{fmt(e['parts']['heading']['nees_mean'])} | {nis['mean']:.3f} | {nis['fraction_above_95']:.4f} | "
                   f"{e['landmark_rmse_m']:.4f} |")
    out.append("")
    best = max((m for m in modes if m != "textbook"), key=lambda m: planar[m]["fraction_inside"])
    for m, name in (("first_estimates", "First-estimates Jacobians"), ("invariant", "The invariant EKF")):
        if m not in planar:
            continue
        e = planar[m]
        verdict = "meets" if e["fraction_inside"] >= 0.90 else "misses"
        out.append(f"{name} keep{'s' if m == 'invariant' else ''} the ensemble-average NEES inside its 95% bounds "
                   f"at {e['fraction_inside']:.3f} of the steps or more in every ensemble, so the filter {verdict} "
                   "the target of 0.90 per seed.")
        out.append("")
    out.append(f"The textbook EKF manages {planar['textbook']['fraction_inside']:.3f} in its worst ensemble. The "
               f"mode with the highest worst-ensemble share here is `{best}`.")
    if "invariant" in planar and "first_estimates" in planar:
        inv, fej = planar["invariant"], planar["first_estimates"]
        wins = sum(a > b for a, b in zip(inv["fraction_inside_by_seed"], fej["fraction_inside_by_seed"]))
        out.append("")
        out.append(f"Paired by seed (the two filters see the same worlds and noise), the invariant EKF has the higher "
                   f"share inside in {wins} of the {len(inv['fraction_inside_by_seed'])} ensembles; its landmark RMS "
                   f"is {inv['landmark_rmse_m']:.4f} m against {fej['landmark_rmse_m']:.4f} m for first estimates "
                   f"and {planar['textbook']['landmark_rmse_m']:.4f} m for the textbook filter.")
    return out


MONOCULAR_MODES = ("textbook", "first_estimates", "iterated", "observability_constrained", "ideal",
                   "camera_velocity/textbook", "camera_velocity/observability_constrained", "camera_velocity/ideal")
LO6, HI6 = 1.24, 12.6  # the two-sided 95% range of one chi-square(6) sample


def mode_name(m):
    return m.replace("camera_velocity/", "") + " (velocity in the camera frame)" if m.startswith("camera_velocity/") else m


def monocular_table(suite, modes=MONOCULAR_MODES):
    out = ["| pipeline | mode | NEES mean | median run | 95% bounds | fraction inside | position median run | "
           "orientation median run | convergence | e_l converged (m^2) | e_t converged (m^2) |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for key, name in PIPELINES:
        for m in modes:
            e = suite.get(f"{key}/{m}")
            if e is None:
                continue
            out.append(f"| {name} | {mode_name(m)} | {fmt(e['nees_mean'])} | {fmt(e['nees_median_run'])} | {bounds(e)} | "
                       f"{e['fraction_inside']:.3f} | {fmt(e['parts']['position']['nees_median_run'])} | "
                       f"{fmt(e['parts']['orientation']['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                       f"{fmt(e['landmark_error_converged_m2'], 3)} | {fmt(e['trajectory_error_converged_m2'], 4)} |")
    return out


FACTORS = [
    ("linearization", ("textbook", "ideal"), "linearization: textbook -> ideal"),
    ("pixel noise", ("default_pixel_noise", "true_pixel_noise"), "pixel noise told: 1.5 px -> the true 1 px"),
    ("gate", ("gate", "no_gate"), "NIS gate: on -> off"),
    ("points", ("ellipse_centre_points", "unbiased_points"), "point (u, v): ellipse centre -> unbiased"),
    ("accel", ("default_accel", "raised_accel"), "acceleration noise: default -> raised"),
]


def median_nees(e):
    v = e["nees_median_run"]
    return math.inf if v is None else v


def paired_effect(cells, pipeline, index, within=None):
    """Pairs of cells of `pipeline` that differ in factor `index` alone (and, if `within` is
    (position, level), share that level): geometric-mean ratio of nees_median_run after/before,
    pairs lower, median convergence before and after."""
    a, b = FACTORS[index][1]
    logs, lower, pairs, conv_a, conv_b = [], 0, 0, [], []
    for key, e in cells.items():
        if key[0] != pipeline or key[1 + index] != a:
            continue
        if within is not None and key[1 + within[0]] != within[1]:
            continue
        other = list(key)
        other[1 + index] = b
        f = cells.get(tuple(other))
        if f is None:
            continue
        pairs += 1
        x, y = median_nees(e), median_nees(f)
        if math.isfinite(x) and math.isfinite(y) and x > 0 and y > 0:
            logs.append(math.log(y / x))
        if y < x:
            lower += 1
        conv_a.append(e["convergence_ratio"])
        conv_b.append(f["convergence_ratio"])
    g = math.exp(statistics.fmean(logs)) if logs else math.nan
    return g, lower, pairs, statistics.median(conv_a), statistics.median(conv_b)


def factor_section(factors):
    cells = {tuple(key.split("/")): e for key, e in factors.items()}
    out = ["Each row compares the cells that differ in one factor only, the others held at each of their "
           "combinations (paired: the same noise draws in both): the geometric mean over those pairs of the "
           "ratio of the camera-pose `nees_median_run` (after / before; below 1: more consistent), how many "
           "pairs it lowered, and the median convergence ratio before and after. The effect of linearization "
           "is over all 16 combinations of the other factors; the others are shown for the textbook and the "
           "ideal filter apart (8 pairs each), because some act in opposite directions on the two.", "",
           "| pipeline | factor | filter | NEES ratio | pairs lower | convergence before -> after |",
           "|---|---|---|---|---|---|"]
    effects = {}
    for pipeline, name in PIPELINES:
        g, lower, pairs, ca, cb = paired_effect(cells, pipeline, 0)
        effects[(pipeline, "linearization", None)] = g
        out.append(f"| {name} | {FACTORS[0][2]} | both | {g:.3g} | {lower} of {pairs} | {ca:.2f} -> {cb:.2f} |")
        for index in range(1, len(FACTORS)):
            for level in ("textbook", "ideal"):
                g, lower, pairs, ca, cb = paired_effect(cells, pipeline, index, within=(0, level))
                effects[(pipeline, FACTORS[index][0], level)] = g
                out.append(f"| {name} | {FACTORS[index][2]} | {level} | {g:.3g} | {lower} of {pairs} | "
                           f"{ca:.2f} -> {cb:.2f} |")
    out.append("")
    out.append("The lowest `nees_median_run` of each pipeline in the factorial, beside the cell of today's defaults "
               "(position and orientation alone: 3 dof each):")
    out.append("")
    out.append("| pipeline | cell | NEES median run | position | orientation | convergence | e_l converged (m^2) | "
               "e_t converged (m^2) |")
    out.append("|---|---|---|---|---|---|---|---|")
    best_cells = {}
    for pipeline, name in PIPELINES:
        mine = {k: e for k, e in cells.items() if k[0] == pipeline}
        best = min(mine, key=lambda k: median_nees(mine[k]))
        best_cells[pipeline] = (best, mine[best])
        default = (pipeline, "textbook", "default_pixel_noise", "gate", "ellipse_centre_points", "default_accel")
        for label, k in (("lowest", best), ("defaults", default)):
            e = mine[k]
            out.append(f"| {name} | {label}: `{'/'.join(k[1:])}` | {fmt(e['nees_median_run'])} | "
                       f"{fmt(e['parts']['position']['nees_median_run'])} | "
                       f"{fmt(e['parts']['orientation']['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                       f"{fmt(e['landmark_error_converged_m2'], 3)} | {fmt(e['trajectory_error_converged_m2'], 4)} |")
    return out, effects, best_cells


def findings(effects, best_cells, monocular):
    """The conclusions, each computed from the numbers above."""
    out = ["## What the experiment says", ""]
    lo, hi = LO6, HI6
    for pipeline, name in PIPELINES:
        accel_ideal = effects[(pipeline, "accel", "ideal")]
        accel_textbook = effects[(pipeline, "accel", "textbook")]
        gate_textbook = effects[(pipeline, "gate", "textbook")]
        noise_ideal = effects[(pipeline, "pixel noise", "ideal")]
        points_textbook = effects[(pipeline, "points", "textbook")]
        best, e = best_cells[pipeline]
        inside = lo <= median_nees(e) <= hi
        out.append(f"- **{name}.** Raising the acceleration noise multiplies the ideal filter's median NEES by "
                   f"{accel_ideal:.3g} and the textbook filter's by {accel_textbook:.3g}; switching the gate off "
                   f"multiplies the textbook filter's by {gate_textbook:.3g}; telling the filter the true pixel noise "
                   f"multiplies the ideal filter's by {noise_ideal:.3g}; removing the point models' bias multiplies "
                   f"the textbook filter's by {points_textbook:.3g}. Its most consistent cell, "
                   f"`{'/'.join(best[1:])}`, has a median of {fmt(median_nees(e))}, "
                   f"{'inside' if inside else 'outside'} the range [{lo}, {hi}] of one 6-dof sample.")
    out.append("")
    out.append("Read together (the ratios above are the evidence; each claim is printed only where they hold):")
    out.append("")
    keys = [p for p, _ in PIPELINES]
    motion_first = all(effects[(p, "accel", "ideal")] < 0.2 for p in keys)
    linearization_second = all(effects[(p, "accel", "textbook")] > 1.0 for p in keys)
    gate_needed = all(effects[(p, "gate", "textbook")] > 2.0 for p in keys)
    minor = all(abs(math.log(effects[(p, "points", "textbook")])) < abs(math.log(effects[(p, "accel", "ideal")]))
                for p in keys)
    if motion_first:
        out.append("1. **The motion model is the first cause.** The camera drives at constant speed along curves, "
                   "so its acceleration is not white noise: it points into each turn for seconds at a time. "
                   "Our reading of why: monocular SLAM cannot observe scale from the images, so the only scale "
                   "information in the filter comes from its priors, and the constant-velocity model's "
                   "acceleration prior is the strongest (a smaller scale needs smaller accelerations through the "
                   "same turns); with the default acceleration noise that prior is too confident, and the filter "
                   "trusts a scale the turns have pulled away. What the tables show: the position NEES carries "
                   "almost all of the pose NEES while the orientation stays near its 3 dof, and even the ideal filter, "
                   "which has no linearization error, is inconsistent by orders of magnitude with the default "
                   "acceleration noise, and raising it lowers the ideal filter's NEES by more than five times in "
                   "every pipeline.")
    else:
        out.append("1. The acceleration noise does not lower the ideal filter's NEES by more than five times in "
                   "every pipeline: the data do not single out the motion model.")
    if linearization_second:
        out.append("2. **Linearization is the second cause.** With the raised acceleration noise the textbook filter "
                   "does not follow the ideal one: its NEES rises in every pipeline (our reading: a weaker motion "
                   "prior leaves more room for the scale information a filter invents by linearizing at "
                   "changing estimates; the experiment shows the rise, not its mechanism).")
    else:
        out.append("2. Raising the acceleration noise does not raise the textbook filter's NEES in every pipeline.")
    if gate_needed:
        out.append("   The NIS gate is what keeps the textbook filter from diverging: without it its NEES grows "
                   "more than twice in every pipeline.")
    if minor:
        out.append("3. **The point model's bias is minor**: removing it moves the textbook filter's NEES less than "
                   "the acceleration noise moves the ideal filter's. Telling the filter the true 1 px instead of "
                   "1.5 px makes it more confident, and its NEES rises accordingly.")
    fs = monocular.get("first_sight/first_estimates")
    if fs is not None:
        out.append(f"4. **First-estimates Jacobians on the monocular filter.** On the default forest the "
                   f"width-from-first-sight pipeline converges in {fs['convergence_ratio']:.2f} of the draws with "
                   f"them (median NEES {fmt(fs['nees_median_run'])}). An inverse-depth landmark's "
                   "first estimate is its depth prior (rho = 0.1 +- 0.5), not a measurement, so the Jacobians taken "
                   "there can be far from the truth (our reading; the table shows the divergence).")
    rows = []
    near_ideal = True
    for pipeline, name in PIPELINES:
        it, tb, ideal = (monocular.get(f"{pipeline}/{m}") for m in ("iterated", "textbook", "ideal"))
        if it is None or tb is None or ideal is None:
            continue
        ratio = median_nees(it) / median_nees(ideal)
        near_ideal = near_ideal and 0.5 < ratio < 2.0
        rows.append(f"{name}: {fmt(it['nees_median_run'])} (textbook {fmt(tb['nees_median_run'])}, ideal "
                    f"{fmt(ideal['nees_median_run'])}; convergence {it['convergence_ratio']:.2f}, textbook "
                    f"{tb['convergence_ratio']:.2f})")
    if rows:
        verdict = ("within a factor of two of the ideal filter's in every pipeline: iterating each update removes "
                   "most of the linearization error, and what is left is the motion model's error of cause 1, "
                   "which the textbook filter's linearization error masks in part (our reading)"
                   if near_ideal else "not within a factor of two of the ideal filter's in every pipeline")
        out.append("5. **The iterated update on the monocular filter** (default forest; median NEES per run): " +
                   "; ".join(rows) + f". Its NEES is {verdict}.")
    out.append("")
    return out


def runnable_modes(suite, pipeline):
    """The modes of `pipeline` one can run (not the ideal diagnostic), with their entries."""
    return [(m, suite[f"{pipeline}/{m}"]) for m in MONOCULAR_MODES
            if not m.endswith("ideal") and f"{pipeline}/{m}" in suite]


def target_verdict(monocular, forests):
    """The issue's monocular target, judged from the numbers for every runnable mode."""
    out = ["## The monocular target", "",
           f"The target: a median NEES per run inside [{LO6}, {HI6}] (the two-sided 95% range of one 6-dof sample) on "
           "the default forest, with landmark and trajectory errors no larger than today's (the textbook filter with "
           "the velocity in the world frame, the pipelines' default) and a convergence ratio over the 30 forests no "
           "lower than today's. Every runnable mode is judged against each condition; the ideal filter is a "
           "diagnostic, shown as the floor.", ""]
    out.append("| pipeline | mode | NEES median run | convergence | e_l converged (m^2) | e_t converged (m^2) | "
               "30 forests: NEES median run | 30 forests: convergence | verdict |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    met_by = {}
    for pipeline, name in PIPELINES:
        today = monocular.get(f"{pipeline}/textbook")
        today_forests = forests.get(f"{pipeline}/textbook")
        if today is None or today_forests is None:
            continue
        rows = runnable_modes(monocular, pipeline)
        rows += [(m, monocular[f"{pipeline}/{m}"]) for m in ("ideal", "camera_velocity/ideal") if f"{pipeline}/{m}" in monocular]
        for m, e in rows:
            f = forests.get(f"{pipeline}/{m}", {})
            if m.endswith("ideal"):
                verdict = "floor (diagnostic)"
            else:
                el, et = e["landmark_error_converged_m2"], e["trajectory_error_converged_m2"]
                checks = (("NEES outside the range", LO6 <= median_nees(e) <= HI6),
                          ("larger errors", el is not None and et is not None
                           and el <= today["landmark_error_converged_m2"] and et <= today["trajectory_error_converged_m2"]),
                          ("lower convergence over the forests",
                           bool(f) and f["convergence_ratio"] >= today_forests["convergence_ratio"]))
                failed = [w for w, ok in checks if not ok]
                verdict = "**met**" if not failed else "not met: " + ", ".join(failed)
                if not failed:
                    met_by.setdefault(pipeline, []).append(m)
            forest_conv = f"{f['convergence_ratio']:.2f}" if f else "-"
            out.append(f"| {name} | {mode_name(m)} | {fmt(e['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                       f"{fmt(e['landmark_error_converged_m2'], 3)} | {fmt(e['trajectory_error_converged_m2'], 4)} | "
                       f"{fmt(f.get('nees_median_run'))} | {forest_conv} | {verdict} |")
    out.append("")
    for pipeline, name in PIPELINES:
        modes = met_by.get(pipeline, [])
        out.append(f"- **{name}**: " + (f"the target is met by {', '.join('`' + mode_name(m) + '`' for m in modes)}."
                                         if modes else "no runnable mode meets the target."))
    out.append("")
    return out, met_by


def binomial_two_sided(k, n):
    """Exact two-sided p of k successes in n fair trials (the sign test, McNemar's exact test)."""
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, i) for i in range(0, min(k, n - k) + 1)) / 2 ** n
    return min(1.0, 2 * tail)


def median_interval(values, level=0.95):
    """The median and its distribution-free confidence interval from order statistics."""
    v = sorted(values)
    n = len(v)
    if n == 0:
        return math.nan, math.nan, math.nan
    k = 0
    while k + 1 <= n and sum(math.comb(n, i) for i in range(0, k + 1)) / 2 ** n <= (1 - level) / 2:
        k += 1
    lo, hi = (v[k - 1], v[n - k]) if k >= 1 else (v[0], v[-1])
    return statistics.median(v), lo, hi


def manifold_section(manifold):
    """The camera on its manifold against its quaternion, paired run by run on forests 101 and up."""
    any_entry = next(iter(manifold.values()))
    out = ["## The camera on its manifold (`monocular-manifold`)", "",
           "`OnManifold<ConstantVelocity3D>` keeps the camera's covariance on its 12-dimensional tangent and moves "
           "the camera through ⊕ in each update ([filter.md](filter.md), \"Robots on manifolds\"); the quaternion "
           "filter keeps the quaternion's four entries in the covariance and renormalizes after each update. Both "
           f"with the velocity in the camera frame, one run on each of {any_entry['runs']} forests (seeds 101 and "
           "up, which no other suite scores), the same scenarios for both, so they are compared run by run:", "",
           "| pipeline | filter | camera state | NEES median run | position | orientation | convergence | "
           "e_l converged (m^2) | e_t converged (m^2) |",
           "|---|---|---|---|---|---|---|---|---|"]
    for pipeline, name in PIPELINES:
        for mode in ("textbook", "observability_constrained"):
            for state in ("quaternion", "manifold"):
                e = manifold.get(f"{pipeline}/{mode}/{state}")
                if e is None:
                    continue
                out.append(f"| {name} | {mode} | {state} | {fmt(e['nees_median_run'])} | "
                           f"{fmt(e['parts']['position']['nees_median_run'])} | "
                           f"{fmt(e['parts']['orientation']['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                           f"{fmt(e['landmark_error_converged_m2'], 3)} | {fmt(e['trajectory_error_converged_m2'], 4)} |")
    out.append("")
    out.append("Paired, forest by forest: how many converge with one camera state and not the other (McNemar's "
               "exact test), and the ratio of each run's time-averaged pose NEES, manifold over quaternion, over the "
               "runs where both are finite (median with its distribution-free 95% interval; sign test of ratio = 1):")
    out.append("")
    out.append("| pipeline | filter | converged: manifold only | quaternion only | McNemar p | NEES ratio median "
               "[95% interval] | runs | sign test p |")
    out.append("|---|---|---|---|---|---|---|---|")
    agree = []
    for pipeline, name in PIPELINES:
        for mode in ("textbook", "observability_constrained"):
            q = manifold.get(f"{pipeline}/{mode}/quaternion")
            m = manifold.get(f"{pipeline}/{mode}/manifold")
            if q is None or m is None or "run_nees" not in q:
                continue
            only_m = sum(1 for a, b in zip(m["run_converged"], q["run_converged"]) if a and not b)
            only_q = sum(1 for a, b in zip(m["run_converged"], q["run_converged"]) if b and not a)
            ratios = [a / b for a, b in zip(m["run_nees"], q["run_nees"])
                      if a is not None and b is not None and b > 0 and math.isfinite(a) and math.isfinite(b)]
            med, lo, hi = median_interval(ratios)
            above = sum(1 for r in ratios if r > 1)
            below = sum(1 for r in ratios if r < 1)
            out.append(f"| {name} | {mode} | {only_m} | {only_q} | {binomial_two_sided(only_m, only_m + only_q):.3f} | "
                       f"{fmt(med, 3)} [{fmt(lo, 3)}, {fmt(hi, 3)}] | {len(ratios)} | "
                       f"{binomial_two_sided(below, above + below):.3f} |")
            agree.append(only_m == 0 and only_q == 0 and 0.98 <= lo and hi <= 1.02)
    out.append("")
    if agree and all(agree):
        out.append("The two camera states agree run by run: the same forests converge, and each run's NEES moves by "
                   "less than 2% (the intervals above). The tangent covariance does not change what the filters "
                   "estimate or how consistent they are: the quaternion filter's normalization Jacobian already "
                   "keeps its covariance on the tangent to first order, so the over-confidence of the textbook "
                   "filter comes from its linearization (sections above), not from the quaternion. The manifold "
                   "state is the cleaner covariance (six degrees of freedom of pose, no singular direction to "
                   "carry).")
    else:
        out.append("The two camera states differ in at least one pipeline and filter beyond 2% of the NEES or in "
                   "which forests converge: see the paired table.")
    out.append("")
    return out


def gauge_section(gauge):
    """The two left inverses of the observability-constrained transport, on forests 101 and up."""
    any_entry = next(iter(gauge.values()))
    out = ["## Which left inverse for the observability-constrained update (`monocular-gauge`)", "",
           "The transport T = I + dN A of the observability-constrained update works with any left inverse A of the "
           "unobservable directions ([filter.md](filter.md)). The two that sylva offers (`GaugeInverse`), with the "
           f"velocity in the camera frame, one run on each of {any_entry['runs']} forests (seeds 101 and up, which no "
           "other suite scores):", "",
           "| pipeline | left inverse | NEES median run | convergence | e_l converged (m^2) | e_t converged (m^2) |",
           "|---|---|---|---|---|---|"]
    for pipeline, name in PIPELINES:
        for inverse, label in (("robot", "the robot's coordinates (default)"), ("whole_state", "the whole state")):
            e = gauge.get(f"{pipeline}/{inverse}")
            if e is None:
                continue
            out.append(f"| {name} | {label} | {fmt(e['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                       f"{fmt(e['landmark_error_converged_m2'], 3)} | {fmt(e['trajectory_error_converged_m2'], 4)} |")
    out.append("")
    better = all(gauge[f"{p}/robot"]["convergence_ratio"] >= gauge[f"{p}/whole_state"]["convergence_ratio"]
                 for p, _ in PIPELINES if f"{p}/robot" in gauge and f"{p}/whole_state" in gauge)
    out.append("The robot's left inverse converges in at least as many runs as the whole state's in every pipeline."
               if better else "The robot's left inverse does not converge in as many runs as the whole state's in "
               "every pipeline; the default deserves a second look.")
    out.append("")
    return out


def motion_section(motion, monocular):
    """The motion-model study on forests 101 and up: the frame of the camera's velocity."""
    out = ["## The motion model: velocity in the world or in the camera frame (`monocular-motion`)", ""]
    any_entry = next(iter(motion.values()))
    out.append("`ConstantVelocity3D` can carry the camera's linear velocity in the world frame (MonoSLAM's model "
               "and the thesis's, the default) or in the camera's own frame "
               "(`ConstantVelocity3D::VelocityFrame::kCamera`). A camera carried along an arc at a steady speed "
               "keeps a constant velocity in its own frame, so there the acceleration noise only has to cover "
               "changes of speed and of heading rate; in the world frame it must also cover the turn itself. "
               f"Each pipeline, the textbook and the ideal filter, one run on each of {any_entry['runs']} forests "
               "(seeds 101 and up, which no other suite scores), 1 px noise, everything else at the pipelines' "
               "defaults. Nothing was chosen from this table: the camera-frame rows of the suites above use the "
               "default acceleration noise, 0.3 m/s^2.")
    out.append("")
    out.append("| pipeline | filter | velocity frame | acceleration sigma (m/s^2) | NEES median run | position median run "
               "| orientation median run | convergence | e_t converged (m^2) | e_l converged (m^2) |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    rows = {}
    for key, e in motion.items():
        pipeline, mode, frame, accel = key.split("/")
        rows[(pipeline, mode, frame, float(accel.replace("accel_", "")))] = e
    accels = sorted({k[3] for k in rows})
    for pipeline, name in PIPELINES:
        for mode in ("textbook", "ideal"):
            for frame in ("world_velocity", "camera_velocity"):
                for accel in accels:
                    e = rows.get((pipeline, mode, frame, accel))
                    if e is None:
                        continue
                    out.append(f"| {name} | {mode} | {frame.replace('_velocity', '')} | {accel:g} | "
                               f"{fmt(e['nees_median_run'])} | {fmt(e['parts']['position']['nees_median_run'])} | "
                               f"{fmt(e['parts']['orientation']['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                               f"{fmt(e['trajectory_error_converged_m2'], 3)} | {fmt(e['landmark_error_converged_m2'], 3)} |")
    out.append("")
    # What the table says, computed.
    lines = []
    for pipeline, name in PIPELINES:
        ideal_world = [median_nees(rows[(pipeline, "ideal", "world_velocity", a)]) for a in accels
                       if (pipeline, "ideal", "world_velocity", a) in rows]
        ideal_camera = [median_nees(rows[(pipeline, "ideal", "camera_velocity", a)]) for a in accels
                        if (pipeline, "ideal", "camera_velocity", a) in rows]
        tb_world = [median_nees(rows[(pipeline, "textbook", "world_velocity", a)]) for a in accels
                    if (pipeline, "textbook", "world_velocity", a) in rows]
        tb_camera = [median_nees(rows[(pipeline, "textbook", "camera_velocity", a)]) for a in accels
                     if (pipeline, "textbook", "camera_velocity", a) in rows]
        if not (ideal_world and ideal_camera and tb_world and tb_camera):
            continue
        inside = [a for a in accels if (pipeline, "ideal", "camera_velocity", a) in rows
                  and LO6 <= median_nees(rows[(pipeline, "ideal", "camera_velocity", a)]) <= HI6]
        lines.append(f"- **{name}.** The ideal filter's median NEES: {', '.join(fmt(v) for v in ideal_world)} with the "
                     f"velocity in the world frame, {', '.join(fmt(v) for v in ideal_camera)} in the camera frame "
                     f"(acceleration sigma {', '.join(f'{a:g}' for a in accels)} m/s^2); inside [{LO6}, {HI6}] at "
                     + (", ".join(f"{a:g}" for a in inside) + " m/s^2" if inside else "none of them") +
                     f". The textbook filter's: {', '.join(fmt(v) for v in tb_world)} (world) and "
                     f"{', '.join(fmt(v) for v in tb_camera)} (camera).")
    out += lines
    out.append("")
    # The default forest, paired: the same noise draws with either motion model.
    pairs = []
    for pipeline, name in PIPELINES:
        for mode in ("ideal", "textbook"):
            w, c = monocular.get(f"{pipeline}/{mode}"), monocular.get(f"{pipeline}/camera_velocity/{mode}")
            if w is not None and c is not None:
                pairs.append((name, mode, w, c))
    if pairs:
        out.append("On the default forest (the `monocular` suite above, the same noise draws for both motion models), "
                   "the median NEES per run goes from world-frame to camera-frame velocity as: " +
                   "; ".join(f"{name}, {mode}: {fmt(w['nees_median_run'])} -> {fmt(c['nees_median_run'])} "
                             f"(convergence {w['convergence_ratio']:.2f} -> {c['convergence_ratio']:.2f})"
                             for name, mode, w, c in pairs) + ".")
        out.append("")
        ideal_cured = all(LO6 <= median_nees(c) <= HI6 for _, mode, _, c in pairs if mode == "ideal")
        textbook_left = all(median_nees(c) > HI6 for _, mode, _, c in pairs if mode == "textbook")
        if ideal_cured:
            out.append("With the velocity in the camera frame the ideal filter is consistent in every pipeline: the "
                       "motion model's error, cause 1 above, is gone, and the floor the issue asks about is inside "
                       "the range of one 6-dof sample.")
        if textbook_left:
            out.append("The textbook filter stays over-confident in every pipeline: what is left is its "
                       "linearization (cause 2). First-estimates Jacobians do not help here (they diverge: their "
                       "landmark Jacobians sit at the inverse-depth prior), nor does the iterated update.")
        oc = [(name, monocular.get(f"{p}/camera_velocity/observability_constrained"), monocular.get(f"{p}/camera_velocity/textbook"))
              for p, name in PIPELINES]
        oc = [(name, o, t) for name, o, t in oc if o is not None and t is not None]
        if oc:
            inside = all(LO6 <= median_nees(o) <= HI6 for _, o, _ in oc)
            out.append("The observability-constrained update ([filter.md](filter.md)), which removes the information the "
                       "textbook update invents along the unobservable directions, on the same draws: " +
                       "; ".join(f"{name}: {fmt(o['nees_median_run'])} (textbook {fmt(t['nees_median_run'])}; "
                                 f"convergence {o['convergence_ratio']:.2f}, textbook {t['convergence_ratio']:.2f})"
                                 for name, o, t in oc) + "." +
                       (" With the velocity in the camera frame it is consistent in every pipeline: the two causes "
                        "the factorial experiment found, the motion model and the linearization, are both answered."
                        if inside else " It is not inside the range in every pipeline."))
        out.append("")
    return out


def main():
    suites = json.load(open(sys.argv[1]))
    factors = json.load(open(sys.argv[2]))["monocular-factors"]
    command = sys.argv[3]
    raised = sys.argv[4] if len(sys.argv) > 4 else "raised"
    lines = ["# Consistency: does the covariance tell the truth?", ""]
    lines.append("Generated by `scripts/consistency_report.py` from the JSON of `examples/consistency`; "
                 f"regenerate with `{command}`. Nothing on this page is typed by hand. Every filter "
                 "runs with the defaults of its example, and the planar suite tells the filter the "
                 "simulator's true noise.")
    lines.append("")
    lines.append("A filter is consistent when its errors are as large as its covariance says: the NEES "
                 "e^T P^-1 e of a consistent filter is chi-square distributed with as many degrees of freedom "
                 "as e has, so its average over N runs lies inside the two-sided 95% bounds "
                 "chi2inv(0.025, N dof) / N and chi2inv(0.975, N dof) / N at 95% of the steps. The modes: "
                 "`textbook` (every Jacobian at the latest estimate), `first_estimates` (FEJ, Huang, Mourikis and "
                 "Roumeliotis 2010), `invariant` (the right-invariant EKF, Barrau and Bonnabel 2015: the error of "
                 "the pose and landmark positions taken in the group SE(2) extended by the landmarks; planar robots "
                 "only), `iterated` (Gauss-Newton iterations of each update, Bell and Cathey 1993), "
                 "`observability_constrained` (textbook Jacobians, and after each update the covariance carried from "
                 "the unobservable directions at the linearization point to those at the new estimate; monocular "
                 "filters, whose life cycle then judges each landmark's uncertainty given the camera) and "
                 "`ideal` (predict and update linearized about the true state, a "
                 "diagnostic with no linearization error at all; [filter.md](filter.md)). A monocular mode written "
                 "`camera_velocity/...` carries the camera's linear velocity in its own frame instead of the world's.")
    lines.append("")
    lines.append("What was chosen on what. The suites `monocular`, `monocular-forests` and `monocular-factors` score; "
                 "nothing was chosen on them. The camera-frame velocity was chosen on the forests of "
                 "`monocular-motion` (seeds 101 and up). The observability-constrained update has no setting; its one "
                 "design choice, reading the unobservable part of a correction off the robot's coordinates rather "
                 "than the whole state's ([filter.md](filter.md)), was first compared during development on forests "
                 "1-8 of `monocular-forests`, and then on the forests of `monocular-gauge` (seeds 101 and up), whose "
                 "section below shows the comparison. The acceleration noise, pixel noise, gate and life-cycle thresholds are the pipelines' "
                 "defaults, unchanged.")
    lines.append("")
    lines.append("## Planar: range-bearing SLAM (`planar`)")
    lines.append("")
    lines += planar_section(suites["planar"])
    lines.append("")
    lines.append("## Monocular tree SLAM on the default forest (`monocular`)")
    lines.append("")
    m = suites["monocular"]
    first = next(iter(m.values()))
    lines.append(f"The default forest of `forest_slam` (seed 26), 1 px noise on u, v and w, {first['runs']} noise "
                 "draws; camera-pose NEES (6 dof) every 10th frame over the whole run, in the filter's own frame "
                 "(it starts at the true first pose). The filter's noise is the pipelines' default (1.5 px on u, "
                 "v; 1 px on w; 0.3 m/s^2 and 0.3 rad/s^2 of acceleration). Errors are those of the converged "
                 "runs after similarity alignment, as in the thesis.")
    lines.append("")
    lines += monocular_table(m)
    lines.append("")
    lines.append("## Monocular tree SLAM over 30 forests (`monocular-forests`)")
    lines.append("")
    lines += monocular_table(suites["monocular-forests"])
    lines.append("")
    target, _ = target_verdict(suites["monocular"], suites["monocular-forests"])
    lines += target
    lines.append("## Why the monocular filters are over-confident: the factorial experiment (`monocular-factors`)")
    lines.append("")
    any_factor = next(iter(factors.values()))
    lines.append(f"Five factors, each at two levels, every combination, for each pipeline, on {any_factor['runs']} "
                 "noise draws of the default forest: where the filter linearizes (textbook or ideal), the pixel "
                 "noise it is told (the default 1.5 px or the true 1 px), the NIS gate (on or off), what the point "
                 "models are given as (u, v) (the centre of the base ellipse, which they do not predict, or the "
                 "projection of the true base centre plus the same noise: no model bias), and the linear "
                 "acceleration noise of the constant-velocity model (the default 0.3 m/s^2, or raised to "
                 f"{raised} m/s^2: the sharpest turn of the default path turns the velocity by 90 degrees, 1.4 m/s, "
                 "in about 4 s, which a white acceleration of sigma_a covers at one sigma when "
                 "sigma_a sqrt(T dt) = 1.4 m/s, sigma_a = 2.3 m/s^2, rounded up).")
    lines.append("")
    section, effects, best_cells = factor_section(factors)
    lines += section
    lines.append("")
    lines += findings(effects, best_cells, suites["monocular"])
    lines.append("")
    if len(sys.argv) > 6:
        motion_file = json.load(open(sys.argv[6]))
        lines += motion_section(motion_file["monocular-motion"], suites["monocular"])
        lines.append("")
        if "monocular-gauge" in motion_file:
            lines += gauge_section(motion_file["monocular-gauge"])
        if "monocular-manifold" in motion_file:
            lines += manifold_section(motion_file["monocular-manifold"])
    if len(sys.argv) > 5:
        lines += tuning_section(json.load(open(sys.argv[5]))["monocular-tuning"])
        lines.append("")
    sys.stdout.write("\n".join(lines) + "\n")


def tuning_section(tuning):
    """The acceleration-noise study on forests 101 and up, which no other suite scores."""
    out = ["## Does more acceleration noise cure it? (`monocular-tuning`)", ""]
    any_entry = next(iter(tuning.values()))
    out.append(f"The linear acceleration noise of the constant-velocity model for each pipeline and for the textbook "
               f"and first-estimates filters, one run on each of {any_entry['runs']} forests (seeds 101 and up: no "
               "other suite and no default was chosen on them), 1 px noise; everything else at the pipelines' "
               "defaults. The ideal filter of the factorial experiment shows what the noise would do without "
               "linearization error; this shows what it does to the filters one can run.")
    out.append("")
    out.append("| pipeline | mode | acceleration sigma (m/s^2) | NEES median run | position median run | "
               "orientation median run | convergence | e_t converged (m^2) | e_l converged (m^2) |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    rows = {}
    for key, e in tuning.items():
        pipeline, mode, accel = key.split("/")
        accel = float(accel.replace("accel_", ""))
        rows.setdefault((pipeline, mode), []).append((accel, e))
    for pipeline, name in PIPELINES:
        for mode in ("textbook", "first_estimates"):
            for accel, e in sorted(rows.get((pipeline, mode), []), key=lambda r: r[0]):
                out.append(f"| {name} | {mode} | {accel:g} | {fmt(e['nees_median_run'])} | "
                           f"{fmt(e['parts']['position']['nees_median_run'])} | "
                           f"{fmt(e['parts']['orientation']['nees_median_run'])} | {e['convergence_ratio']:.2f} | "
                           f"{fmt(e['trajectory_error_converged_m2'], 3)} | {fmt(e['landmark_error_converged_m2'], 3)} |")
    out.append("")
    for pipeline, name in PIPELINES:
        series = sorted(rows.get((pipeline, "textbook"), []), key=lambda r: r[0])
        if not series:
            continue
        medians = [median_nees(e) for _, e in series]
        best_accel, best = min(series, key=lambda r: median_nees(r[1]))
        rising = all(b >= a for a, b in zip(medians, medians[1:]))
        out.append(f"- **{name}, textbook.** The median NEES is lowest at {best_accel:g} m/s^2 "
                   f"({fmt(median_nees(best))}, convergence {best['convergence_ratio']:.2f}) and "
                   + ("rises with every step of the acceleration noise" if rising else "does not fall steadily as the "
                      "acceleration noise grows") +
                   f" (to {fmt(medians[-1])} at {series[-1][0]:g} m/s^2). Its orientation NEES median stays between "
                   f"{min(e['parts']['orientation']['nees_median_run'] for _, e in series):.2f} and "
                   f"{max(e['parts']['orientation']['nees_median_run'] for _, e in series):.2f}"
                   + ("; the position part (3 dof) is the larger at every acceleration noise, so most of the "
                      "over-confidence is in position (scale)."
                      if all(e['parts']['position']['nees_median_run'] > e['parts']['orientation']['nees_median_run']
                             for _, e in series) else "."))
    fej = [e for (p, m), rs in rows.items() if m == "first_estimates" for _, e in rs]
    if fej:
        out.append(f"- **First estimates** converge in at most {max(e['convergence_ratio'] for e in fej):.2f} of the "
                   "runs at any acceleration noise.")
    out.append("")
    out.append("So on forests that nothing was tuned on, raising the acceleration noise does not make the filters "
               "that can run consistent: the textbook filter's NEES grows with it, although the ideal filter's falls "
               "(factorial experiment above). Our reading: with more freedom in the motion, each update's "
               "linearization error grows faster than the covariance that should cover it. The default (0.3 m/s^2) stays, and what "
               "remains to try is a linearization that does not invent scale information at the current "
               "estimate." if all(min(rows[(p, 'textbook')], key=lambda r: median_nees(r[1]))[0] == min(a for a, _ in rows[(p, 'textbook')]) for p, _ in PIPELINES if (p, 'textbook') in rows)
               else "The acceleration noise that minimizes the textbook filter's NEES differs from the default in at "
               "least one pipeline; see the table.")
    return out


if __name__ == "__main__":
    main()
