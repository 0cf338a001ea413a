"""thetad's figures: one style (style.py) for every figure of the project, the figures of a flight
(run.py, from a `thetad plot` manifest read by results.py), of the σmax fit (tuning.py) and of the
benchmarks (bench.py), the paper's figure numbers (paper.py). docs/figures.md describes them."""
