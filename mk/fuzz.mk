# Fuzzing: each reader for FUZZ_SECONDS, one at a time, niced (docs/reliability.md).
#
# libFuzzer from Debian's clang (installed here when missing: the main build does not need
# it). Corpora and crashing inputs stay outside git, in runs/fuzz/<target>/; a crash found
# becomes a committed regression input under tests/data/fuzz/<target>/. One process per
# target (libFuzzer's -fork mode restarts the process for every job, and the NetCDF
# targets' setup then takes the whole job); it stops at the first crash, which the report
# names. The files the structure-editing inputs write are valid HDF5, so the libhdf5 probe
# (a fork per file read) is skipped for them: FLOTSAM_NO_PROBE=1; the byte-mutation inputs
# (first byte 0xF0 and above) turn it on for their files.

##@ Fuzzing (docs/reliability.md)
## FUZZ_SECONDS  seconds per fuzz target (600)
FUZZ_SECONDS ?= 600
## FUZZ_TARGETS  the readers to fuzz (csv toml settings scene flow sweep)
FUZZ_TARGETS ?= csv toml settings scene flow sweep
FUZZ_BUILD   ?= build-fuzz
FUZZ_PACKAGES := clang-14 libclang-rt-14-dev

.PHONY: fuzz fuzz-build
## fuzz-build    install clang-14 when missing, build the fuzz targets in build-fuzz/
fuzz-build:
	$(call apt_install,fuzz,$(FUZZ_PACKAGES))
	CC=clang-14 CXX=clang++-14 cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFLOTSAM_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
## fuzz          run each fuzz target for FUZZ_SECONDS and report
fuzz: fuzz-build
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(RUNS)/fuzz/$$t/corpus $(RUNS)/fuzz/$$t/crashes; \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s (log $(RUNS)/fuzz/$$t/log.txt)"; \
	  ASAN_OPTIONS=detect_leaks=0 FLOTSAM_NO_PROBE=1 nice -n 10 $(FUZZ_BUILD)/fuzz_$$t $(RUNS)/fuzz/$$t/corpus fuzz/seeds/$$t \
	    -timeout=20 -rss_limit_mb=2048 -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
	    -artifact_prefix=$(RUNS)/fuzz/$$t/crashes/ > $(RUNS)/fuzz/$$t/log.txt 2>&1; \
	  $(PYTHON) -m pipelines.fuzz_report $$t $(RUNS)/fuzz/$$t; \
	done
