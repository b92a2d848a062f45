"""Folders of the repository that tests read: the experiments, their example surfaces, the asv benchmarks."""

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXPERIMENTS = ROOT / "experiments"
SURFACES = EXPERIMENTS / "surfaces"
BENCHMARKS = ROOT / "benchmarks"
