# Where the jobs run: here, or on a cluster (docs/cluster.md).
#
# LAUNCH prefixes every flow, every sweep shard and every run of the accuracy studies:
#   LAUNCH=          here (make -j runs several at once)
#   LAUNCH=srun      each one a Slurm job: srun -N1 -n1 -c<threads> --time --mem --job-name with
#                    the requests of its kind below; srun options may follow the word
#                    (LAUNCH="srun --partition=short --account=coast")
#   LAUNCH=sbatch    each one a batch job that make waits for (pipelines/sbatch_run.py), logs
#                    in $(RUNS)/slurm/; requeued when preempted, and a requeued flow continues
#                    from its last checkpoint (FLOW_CHECKPOINT)
#   LAUNCH=ssh HOST  on HOST, in this folder (cd $(CURDIR) && ...); make -j runs several there
#   anything else    used as it is: LAUNCH="nice -n 10", LAUNCH="taskset -c 2"
# The outputs are the same bytes wherever a job runs (the nodes must share this folder).

##@ Cluster variables (docs/cluster.md)
## LAUNCH       prefix of each flow and sweep shard: empty, srun, sbatch, "ssh HOST", or any command
LAUNCH   ?=
## FLOW_CHECKPOINT  simulated s between a flow's checkpoints; a rerun continues from them
FLOW_CHECKPOINT ?=
## SHARDS       the sweep as this many jobs, merged at the end (same bytes)
SHARDS   ?= 1
## SHARD_THREADS  threads of one sweep shard (THREADS)
SHARD_THREADS ?= $(THREADS)

# Slurm requests per kind of job: wall-clock minutes and MB of memory (cores: the threads),
# three times the measured time (at least 10 minutes) and twice the measured memory
# (docs/cluster.md). Processor time of a 420 s flow on one thread at 4 cm: 90 s nested,
# 200 s on one uniform grid (NEST_RATIO=1); RES^-3 (cells x4, steps x2 per halving).
# Resident memory: 75 MB + 100 MB x (1 cm / RES)^2.
FLOW_CPU_S_4CM := $(if $(filter 1,$(NEST_RATIO)),200,90)
FLOW_MINUTES ?= $(call slurm_minutes,3 * $(FLOW_CPU_S_4CM) * (0.04 / $(RES)) ^ 3 * $(DURATION) / 420)
FLOW_MEM_MB  ?= $(call flow_mem_mb,$(RES))
# A shard: about 0.25 processor s per 420 s body-run at 2 cm, and each body-run's trajectory
# adds about 35 kB. The defaults cover 5000 body-runs at 2 cm.
SHARD_MINUTES ?= 60
SHARD_MEM_MB  ?= 1000
# One debris run of the debris accuracy study (18 bodies, seconds).
DEBRIS_MINUTES ?= 10
DEBRIS_MEM_MB  ?= 500

# $(call slurm_minutes,SECONDS): an awk expression of seconds as whole minutes, at least 10.
slurm_minutes = $(shell awk 'BEGIN { m = int(($(1)) / 60) + 1; print (m < 10 ? 10 : m) }')
# $(call flow_mem_mb,RES): twice the resident memory, 75 MB + 100 MB x (1 cm / RES)^2.
flow_mem_mb = $(shell awk 'BEGIN { print int(2 * (75 + 100 * (0.01 / $(1)) ^ 2)) + 1 }')
# The prefixes of a flow and a shard ($* is the realisation, or the shard's index).
LAUNCH_FLOW  = $(call launch,$(THREADS),$(FLOW_MINUTES),$(FLOW_MEM_MB),flow-$(TAG)-r$*)
LAUNCH_SHARD = $(call launch,$(SHARD_THREADS),$(SHARD_MINUTES),$(SHARD_MEM_MB),sweep-$(TAG)-$*of$(SHARDS))
# $(call launch,THREADS,MINUTES,MEM_MB,NAME): the prefix that runs one job.
launcher = $(notdir $(firstword $(LAUNCH)))
slurm_requests = -N1 -n1 -c$(1) --time=$(2) --mem=$(3)M --job-name=$(4)
launch = $(strip $(if $(filter srun,$(launcher)),$(LAUNCH) $(slurm_requests),\
                 $(if $(filter sbatch,$(launcher)),$(sbatch_prefix),\
                 $(if $(filter ssh,$(launcher)),$(LAUNCH) cd $(CURDIR) \&\&,$(LAUNCH)))))
sbatch_prefix = $(PYTHON) -m pipelines.sbatch_run $(wordlist 2,$(words $(LAUNCH)),$(LAUNCH)) \
                $(slurm_requests) --output=$(RUNS)/slurm/%x-%j.log --
