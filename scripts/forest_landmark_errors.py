#!/usr/bin/env python3
"""Where forest_slam's map error e_l comes from, landmark by landmark (a diagnostic).

e_l (tree-width thesis, eq. 4.2) is the mean squared distance between the trees mapped in
Euclidean form at the end of lap 1 and the true ones, after the similarity alignment. Being a
mean of squares, a few landmarks far off can carry most of it. This runs one pipeline on one
forest through the Python package, as python/examples/forest_run.py does, and lists the
landmarks by their share of e_l, with how many sightings each took and whether its tree has
another landmark (a duplicate). Needs the package (README, "From Python"):

    build/python-venv/bin/python scripts/forest_landmark_errors.py --seed 26 --association nn

With --duplicates it runs both laps and says in which lap the duplicate landmarks started: in lap 2
they are trees mapped in lap 1 that the association failed to find again (a missed loop closure).
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python" / "examples"))
import forest_run  # noqa: E402  (python/examples/forest_run.py: the scenario and the alignment)
import sylva  # noqa: E402

PIPELINES = {name: pipeline for name, pipeline, _ in forest_run.PIPELINES}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seed", type=int, default=26, help="forest seed (forest_slam's default: 26)")
    parser.add_argument("--pipeline", choices=sorted(PIPELINES), default="with_width")
    parser.add_argument("--association", choices=("ids", "nn"), default="ids")
    parser.add_argument("--pixel-noise", type=float, default=1.0)
    parser.add_argument("--width-noise", type=float, default=1.0)
    parser.add_argument("--top", type=int, default=10, help="landmarks listed")
    parser.add_argument("--unconfirmed-after", type=int, default=0,
                        help="TreeSlamOptions::unconfirmed_after_frames (forest_slam's flag; 0: never)")
    parser.add_argument("--confirm-sightings", type=int, default=3, help="TreeSlamOptions::confirm_sightings")
    parser.add_argument("--duplicates", action="store_true",
                        help="run both laps and say in which lap each duplicate started: a landmark whose first "
                             "sighting's tree already had a landmark with at least --confirm-sightings sightings")
    args = parser.parse_args()
    args.laps = 2
    scenario_options, scenario = forest_run.make_scenario(args)
    options = forest_run.slam_options(args, scenario_options, PIPELINES[args.pipeline])
    if args.association == "nn":
        options.association = sylva.TrunkAssociation.NEAREST_NEIGHBOR
    options.unconfirmed_after_frames = args.unconfirmed_after
    options.confirm_sightings = args.confirm_sightings
    times, laps = scenario.frame_times, scenario.frame_laps
    slam = sylva.MonocularTreeSlam(options, scenario.camera_states[0])
    tree_of, sightings = {}, {}  # landmark -> the tree of the sighting that started it; count
    end_of_lap1 = None
    landmarks_of_tree, duplicate_laps = {}, []
    for k in range(len(scenario)):
        ids, Z, _, _ = scenario.observations(k)
        report = slam.process_frame(0.0 if k == 0 else times[k] - times[k - 1], ids, Z)
        for tree, landmark in zip(ids, report.landmark_of):
            if landmark >= 0:
                if landmark not in tree_of:
                    confirmed = [i for i in landmarks_of_tree.get(tree, []) if sightings[i] >= args.confirm_sightings]
                    if confirmed:
                        duplicate_laps.append(int(laps[k]))
                    landmarks_of_tree.setdefault(tree, []).append(landmark)
                tree_of.setdefault(landmark, tree)
                sightings[landmark] = sightings.get(landmark, 0) + 1
        if laps[k] == 0 and (k + 1 == len(scenario) or laps[k + 1] > 0):
            end_of_lap1 = slam.euclidean_landmarks()
            if not args.duplicates:
                break
    landmarks, positions, _ = end_of_lap1
    trees = np.array([tree_of[i] for i in landmarks], dtype=np.int64)
    T, e_l = forest_run.align(trees, positions, scenario)
    squared = ((np.asarray(T(positions)) - scenario.tree_bases[trees]) ** 2).sum(axis=1)
    per_tree = {}
    for tree in trees:
        per_tree[tree] = per_tree.get(tree, 0) + 1
    print(f"forest {args.seed}, {args.pipeline}, association {args.association}: e_l = {e_l:.3g} m^2 over "
          f"{len(landmarks)} landmarks in Euclidean form at the end of lap 1\n")
    print("| landmark | tree | squared error (m^2) | share of e_l | sightings | its tree has another landmark |")
    print("|---|---|---|---|---|---|")
    total = squared.sum()
    for i in np.argsort(-squared)[:args.top]:
        print(f"| {landmarks[i]} | {trees[i]} | {squared[i]:.3g} | {squared[i] / total:.1%} | "
              f"{sightings.get(landmarks[i], 0)} | {'yes' if per_tree[trees[i]] > 1 else 'no'} |")
    for most in (1, 2):
        few = np.array([sightings.get(i, 0) <= most for i in landmarks])
        print(f"\nlandmarks with at most {most} sighting(s): {few.sum()} of {len(landmarks)}, "
              f"{squared[few].sum() / total:.1%} of e_l")
    if args.duplicates:
        print(f"\nduplicates started (a tree's landmark started while the tree had a confirmed one): "
              + ", ".join(f"lap {lap + 1}: {duplicate_laps.count(lap)}" for lap in sorted(set(laps))))


if __name__ == "__main__":
    main()
