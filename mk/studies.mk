# Studies: runs on the real layout whose CSVs and charts the docs show.

.PHONY: accuracy-hydro accuracy-debris resolution-debris stability-hydro hydro-levers self-nesting

##@ Studies (docs/accuracy.md, docs/studies/)
# Flows at 8, 4 and 2 cm, some on one uniform grid, against the 1 cm flow on the flows'
# nesting; each resolution's launcher asks for the uniform grid's time.
ACCURACY_HYDRO_RES := 0.08 0.04 0.02 0.01
## accuracy-hydro     8, 4, 2 cm flows against 1 cm: docs/data/hydro_accuracy.csv and its chart
accuracy-hydro: build
	$(PYTHON) -m pipelines.accuracy_hydro --dem $(REAL_DEM) --runs $(RUNS)/accuracy --csv docs/data/hydro_accuracy.csv \
	  --duration $(DURATION) --flotsam $(FLOTSAM) --threads $(THREADS) $(if $(LAUNCH),--jobs $(JOBS) $(accuracy_launchers))
	$(PYTHON) -m pipelines.charts_accuracy docs/data/hydro_accuracy.csv docs/img/hydro_error_vs_cost.png
accuracy_launchers = $(foreach r,$(ACCURACY_HYDRO_RES),--launch '$(r)=$(call launch,$(THREADS),$(call \
  slurm_minutes,3 * 200 * (0.04 / $(r)) ^ 3 * $(DURATION) / 420),$(call flow_mem_mb,$(r)),accuracy-hydro-$(r))')

# Debris: stored frame interval x time interpolant, and debris step x integrator, against
# trajectory error (pipelines/accuracy_debris.py), on one 4 cm real-layout flow stored
# every 0.1 s over the city, plus the stability maps of build/debris_stability.
ACC_DEBRIS := $(RUNS)/accuracy-debris
$(ACC_DEBRIS)/flow-0.1s.nc: $(RUNS)/real-0.04.nc
	@mkdir -p $(ACC_DEBRIS)
	$(call launch,$(THREADS),$(call slurm_minutes,3 * 150),$(call flow_mem_mb,0.04),accuracy-debris-flow) \
	  $(FLOTSAM) hydro --scene $< --west pump --duration 420 --output-interval 0.1 --nest-ratio 4 --nest-x -1.2 \
	  --output-window 0.0,8.0,-4.0,0.0 --threads $(THREADS) --label "hydro 0.1s" --out $@
## accuracy-debris    frame interval, interpolant, step and integrator against trajectory error: docs/data/debris_*.csv
accuracy-debris: build $(ACC_DEBRIS)/flow-0.1s.nc
	$(PYTHON) -m pipelines.accuracy_debris --scene $(RUNS)/real-0.04.nc --flow $(ACC_DEBRIS)/flow-0.1s.nc \
	  --runs $(ACC_DEBRIS) --csv-frames docs/data/debris_frames_accuracy.csv --csv-steps docs/data/debris_step_accuracy.csv \
	  --flotsam $(FLOTSAM) --jobs $(JOBS) $(if $(LAUNCH),--launch '$(call launch,1,$(DEBRIS_MINUTES),$(DEBRIS_MEM_MB),accuracy-debris)')
	$(BUILD)/debris_stability > docs/data/debris_stability.csv.part && mv docs/data/debris_stability.csv.part docs/data/debris_stability.csv
	$(PYTHON) -m pipelines.charts_accuracy_debris docs/data docs/img

# The real layout's ten 1 cm flows are the reference; each grid of RESOLUTION_GRIDS is swept
# with the bodies on the 1 cm ground and on the flows' own beds, and copies of the 1 cm flows
# kept to RESOLUTION_FLOOR_BITS significant bits give the chaos floor. Makes only what is
# missing (FLOW_CHECKPOINT=30 lets an interrupted flow continue); pipelines/resolution_study.sh.
## RESOLUTION_GRIDS   grids compared with 1 cm by resolution-debris (0.02 0.04)
RESOLUTION_GRIDS ?= 0.02 0.04
## RESOLUTION_FLOOR_BITS  bits kept in the chaos floor's copies of the 1 cm flows (16 12)
RESOLUTION_FLOOR_BITS ?= 16 12
## resolution-debris  1, 2, 4 cm real-layout flows judged by the debris answer: runs/resolution-debris.md
resolution-debris: build
	MAKE="$(MAKE)" JOBS="$(JOBS)" RUNS="$(RUNS)" PYTHON="$(PYTHON)" FLOTSAM="$(FLOTSAM)" SWEEP_SPEC="$(SWEEP_SPEC)" \
	  REALISATIONS="$(REALISATIONS)" RESOLUTION_GRIDS="$(RESOLUTION_GRIDS)" \
	  RESOLUTION_FLOOR_BITS="$(RESOLUTION_FLOOR_BITS)" pipelines/resolution_study.sh

## stability-hydro    the hydro schemes' step size against outcome: docs/data/hydro_stability.csv and chart
stability-hydro: build
	$(BUILD)/hydro_stability --csv docs/data/hydro_stability.csv
	$(PYTHON) -m pipelines.charts_stability docs/data/hydro_stability.csv docs/img/hydro_stability.png

# The speed levers (time stepping, fronts, dry tolerance, Courant number) at 2 cm over
# 0-150 s against the 1 cm flow: processor time, gauge, arrival and debris errors.
## hydro-levers       each hydro speed lever's cost and error: runs/levers/*.csv
hydro-levers: build
	pipelines/hydro_levers.sh $(FLOTSAM) $(REAL_DEM) $(RUNS) $(wildcard $(RUNS)/speed-ratio/flow-0.02-baseline.nc)

# A box of the real layout at 2 cm driven by a 4 cm run's outline, against the 2 cm run of
# the whole flume, 0-150 s; fails when a tolerance of pipelines/nesting_check.py is passed.
## self-nesting       nesting flotsam in itself, checked: runs/self-nesting/*.csv
self-nesting: build $(RUNS)/bc/wg1_r00.csv
	pipelines/self_nesting.sh $(FLOTSAM) $(REAL_DEM) $(RUNS)/bc/wg1_r00.csv $(RUNS)
