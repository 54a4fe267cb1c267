# Benchmarks: figures printed, never asserted.

.PHONY: bench-hydro bench-debris bench-wetdry bench-sweep bench-slurm

##@ Benchmarks
# Passive OpenMP waits unless set: on a shared machine a spinning thread burns the core
# that the thread it waits for needs. Then the fraction of the machine's limit the flows
# reach at 2 and 1 cm (work per cell-update counted from the kernels, a triad, the
# vector units' rates), the row kernels in float32 against double at 1 cm, and the flows
# against a fixed earlier build, both at once (pipelines/speed_ratio.py builds it under
# $(RUNS) once; 2 cm over 0-150 s and 1 cm over 0-40 s).
## bench-hydro   hydro steps per second, the fraction of the machine's limit, float32 against double, the speed ratio (docs/studies/hydro_speed_levers.md)
bench-hydro: build
	OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive} $(BUILD)/hydro_bench $(if $(REAL_DEM),--dem $(REAL_DEM))
	$(BUILD)/hydro_limit $(if $(REAL_DEM),--dem $(REAL_DEM))
	$(BUILD)/precision_bench $(if $(REAL_DEM),--dem $(REAL_DEM))
	$(PYTHON) -m pipelines.speed_ratio --flotsam $(FLOTSAM) --dem $(REAL_DEM) --runs $(RUNS) --csv $(RUNS)/speed-ratio.csv

## bench-debris  the debris integrator's speed; body steps per second at 100, 1 000, 5 000 bodies alone and in yards that meet
bench-debris: build
	$(BUILD)/debris_bench $(RUNS)/bench --bodies 100,1000,5000 --yards 100,1000,5000 --threads $(JOBS)

# The wet/dry suite (docs/studies/wetdry_suite.md) at CI's size, both front treatments:
# errors against exact solutions, orders, volume, the smallest step, how each run ended.
# `$(BUILD)/wetdry_suite --size full` gives the study's tables.
## bench-wetdry  the wet/dry suite at its small size (docs/studies/wetdry_suite.md)
bench-wetdry: build
	$(BUILD)/wetdry_suite --size small

# The 9-set sweep (10 flows x FD, LD x CC+SC, LC+MC x 9 parameter sets, Cd1 and Cd2 apart)
# with I/O, on the flows at RES (fewer than ten are reused in turn), on GROUND as the sweep is.
## SWEEP_BENCH_FLOWS    the flows bench-sweep reads (the pipeline's)
SWEEP_BENCH_FLOWS   ?= $(FLOWS)
SWEEP_BENCH_THREADS ?= 2
# The debris step's bound [s], 0.02 as the paper's spec files.
SWEEP_BENCH_DT      ?= 0.02
## bench-sweep   the 9-set sweep over the stored flows, with I/O (docs/sweep.md)
bench-sweep: build $(SCENE) $(SWEEP_BENCH_FLOWS) $(GROUND)
	$(omp_passive) $(BUILD)/sweep_bench --threads $(SWEEP_BENCH_THREADS) --dt-max $(SWEEP_BENCH_DT) $(ground_option) \
	  --out $(RUNS)/bench-sweep $(SCENE) $(SWEEP_BENCH_FLOWS)

# The ensemble and a sharded sweep here (make -j1, -j2) and through a Slurm of 1 and 2
# one-core nodes on this machine (docs/cluster.md): wall times, and the same bytes in all.
SCALING_COUNT    ?= 4
SCALING_DURATION ?= 120
## bench-slurm   the ensemble and a sharded sweep here and through a one- and two-node Slurm (docs/cluster.md)
bench-slurm: build
	BUILD=$(BUILD) bench/slurm_scaling.sh $(RES) $(SCALING_COUNT) $(SCALING_DURATION) 4
