# The pipeline from the scene to the charts: each stage a target, each output a file.

REALISATIONS := $(shell seq -f '%02g' 0 $$(( $(COUNT) - 1 )))
BOUNDARIES   := $(foreach r,$(REALISATIONS),$(RUNS)/bc/wg1_r$(r).csv)
FLOWS        := $(foreach r,$(REALISATIONS),$(RUNS)/flows-$(TAG)/flow_r$(r).nc)

##@ Pipeline variables
## SWEEP_SPEC   the sweep's spec (the paper's 7 parameter sets; docs/sweep.md)
SWEEP_SPEC ?= sweep/examples/paper_sensitivity_7.toml
## GROUND       the bodies' ground (the same scene at GROUND_RES under 2 and 4 cm flows; empty: the flows' own)
GROUND_RES ?= 0.01
GROUND ?= $(if $(filter 0.02 0.04,$(RES)),$(if $(filter $(RUNS)/scene-$(RES).nc,$(SCENE)),$(RUNS)/scene-$(GROUND_RES).nc,$(if \
  $(filter $(RUNS)/real-$(RES).nc,$(SCENE)),$(RUNS)/real-$(GROUND_RES).nc)))
## FLOW         the flow that `inspect` shows (the first)
FLOW ?= $(firstword $(FLOWS))
ground_option = $(if $(GROUND),--ground $(GROUND))
STAGE2_TAG := $(TAG)$(if $(GROUND),-on-$(basename $(notdir $(GROUND))))
SWEEP      := $(RUNS)/sweep-$(STAGE2_TAG).nc
STATS      := $(RUNS)/stats-$(STAGE2_TAG).nc
CHARTS     ?= $(RUNS)/charts-$(STAGE2_TAG)

.PHONY: scene real-scene boundaries flows inspect debris sweep stats charts

##@ Stages
## scene        the generated scene at RES (docs/scene.md)
scene: tool $(SCENE)

$(RUNS)/scene-%.nc: | tool
	$(FLOTSAM) scene generate --resolution $* --seed $(SEED) --out $@

## real-scene   the real layout (../shared/data) at RES: runs/real-RES.nc, then SCENE=runs/real-RES.nc
real-scene: tool $(RUNS)/real-$(RES).nc
$(RUNS)/real-%.nc: | tool
	$(FLOTSAM) scene import --dem $(REAL_DEM) --resolution $* --out $@

## boundaries   COUNT WG1 boundary records in runs/bc/
boundaries: tool $(BOUNDARIES)

$(BOUNDARIES) &: | tool
	$(FLOTSAM) boundary generate --out-dir $(RUNS)/bc --count $(COUNT) --seed $(SEED) --duration $(DURATION)

## flows        one flow per record (parallel with -j; through LAUNCH) (docs/hydro.md)
flows: tool $(FLOWS)

$(RUNS)/flows-$(TAG)/flow_r%.nc: $(RUNS)/bc/wg1_r%.csv $(SCENE) $(HYDRO_CONFIG) | tool
	$(LAUNCH_FLOW) $(FLOTSAM) hydro --scene $(SCENE) --west level --west-series $< --realisation $(patsubst 0%,%,$*) \
	  --duration $(DURATION) --output-interval $(OUTPUT_INTERVAL) --threads $(THREADS) \
	  $(if $(NEST_RATIO),--nest-ratio $(NEST_RATIO)) $(if $(NEST_X),--nest-x $(NEST_X)) \
	  $(if $(OUTPUT_WINDOW),--output-window $(OUTPUT_WINDOW)) \
	  --label hydro-r$* --out $@ $(if $(HYDRO_CONFIG),--config $(HYDRO_CONFIG)) $(call checkpoints,$@)

# $(call checkpoints,OUT): checkpoint every FLOW_CHECKPOINT s; continue from OUT's checkpoint if there is one.
checkpoints = $(if $(FLOW_CHECKPOINT),--checkpoint-interval $(FLOW_CHECKPOINT)) $(if $(wildcard $(1).checkpoint.nc),--restart)

## inspect      a flow in ncdump, an xarray summary, and hints for ncview and cdo
inspect: $(FLOW)
	ncdump -h $(FLOW)
	$(PYTHON) -m pipelines.inspect_flow $(FLOW)
	@echo
	@echo "Open it in ncview:  ncview $(FLOW)"
	@echo "With cdo:           cdo sinfon $(FLOW);  cdo -timmax -selname,h $(FLOW) hmax.nc"

## debris       FD and LD (local contact, multiple collisions) through each flow (docs/debris.md)
debris: $(FLOWS)
	@mkdir -p $(RUNS)/debris-$(TAG)
	for f in $(FLOWS); do \
	  $(omp_passive) $(FLOTSAM) debris --flow $$f --scene $(SCENE) $(ground_option) --start FD --start LD \
	    --contact local --collision multi --out $(RUNS)/debris-$(TAG)/$$(basename $$f .nc)_lcmc.nc --quiet || exit 1; \
	done

# Passive OpenMP waits (unless set): the stepping threads meet at a barrier every frame
# interval, and a spinning one takes the core the read-ahead thread needs.
omp_passive   = env OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive}
sweep_command = $(omp_passive) $(FLOTSAM) sweep --spec $(SWEEP_SPEC) --scene $(SCENE) $(ground_option) \
                $(foreach f,$(FLOWS),--flow $(f))

## sweep        SWEEP_SPEC over the stored flows, in SHARDS jobs merged at the end (docs/sweep.md)
sweep: $(SWEEP)
ifeq ($(SHARDS),1)
SWEEP_THREADS := $(if $(LAUNCH),$(SHARD_THREADS),$(JOBS))
$(SWEEP): $(FLOWS) $(SWEEP_SPEC) $(GROUND) | tool
	$(call launch,$(SWEEP_THREADS),$(SHARD_MINUTES),$(SHARD_MEM_MB),sweep-$(TAG)) $(sweep_command) \
	  --threads $(SWEEP_THREADS) --out $@
else
SHARD_DIR   := $(RUNS)/sweep-$(STAGE2_TAG)-shards$(SHARDS)
SHARD_PARTS := $(foreach i,$(shell seq 0 $$(( $(SHARDS) - 1 ))),$(SHARD_DIR)/part$(i).nc)
$(SWEEP): $(SHARD_PARTS)
	$(FLOTSAM) sweep merge $^ --out $@
$(SHARD_DIR)/part%.nc: $(FLOWS) $(SWEEP_SPEC) $(GROUND) | tool
	@mkdir -p $(SHARD_DIR)
	$(LAUNCH_SHARD) $(sweep_command) --shard $*/$(SHARDS) --threads $(SHARD_THREADS) --quiet --out $@
endif

## stats        the paper's statistics of the sweep (NetCDF and CSV)
stats: $(STATS)
$(STATS): $(SWEEP)
	$(FLOTSAM) stats --sweep $< --scene $(SCENE) --out $@ --csv $(RUNS)/stats-$(STAGE2_TAG)

## charts       the charts, in runs/charts-TAG/
charts: $(STATS)
	$(PYTHON) -m pipelines.charts --scene $(SCENE) --flows $(FLOWS) --trajectories $(SWEEP) --stats $(STATS) --out $(CHARTS)
