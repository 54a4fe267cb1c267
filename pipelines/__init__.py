"""flotsam's Python drivers: charts, accuracy studies, flow inspection and timing.

Run them as modules from the repository root, e.g. `python3 -m pipelines.charts --help`.
"""
