# Outputs a planner opens: the GIS export checked in a real QGIS, and the runs as moving
# pictures (docs/gis.md, "In QGIS" and "Moving pictures").

##@ QGIS and moving pictures
## ANIMATE_TRACKS  the bodies `animate` shows: a debris or sweep file through FLOW (the debris run of FLOW)
ANIMATE_TRACKS ?= $(RUNS)/debris-$(TAG)/$(basename $(notdir $(FLOW)))_lcmc.nc
## ANIMATION    where `animate` writes (runs/animation-TAG)
ANIMATION      ?= $(RUNS)/animation-$(TAG)
QGIS_PACKAGES  := qgis python3-qgis
QGIS_TEST      := $(RUNS)/qgis-test
qgis_check      = QT_QPA_PLATFORM=offscreen $(PYTHON) tests/qgis/check_project.py

.PHONY: test-qgis animate real-scale-qgis real-scale-animate

## test-qgis    install Debian's QGIS if missing; a small UTM study; its project opened headless: layers, CRS, styles, pixels
test-qgis: tool
	$(call apt_install,test-qgis,$(QGIS_PACKAGES))
	rm -rf $(QGIS_TEST)
	$(PYTHON) tests/qgis/small_study.py --flotsam $(FLOTSAM) --out $(QGIS_TEST)
	$(qgis_check) $(QGIS_TEST)/gis/project.qgz --crs EPSG:32653 --png-dir $(QGIS_TEST)/png --prefix small

## animate      FLOW and the bodies of ANIMATE_TRACKS as MP4 and GIF in ANIMATION (runs `debris` when missing)
animate: $(FLOW)
	@test -f $(ANIMATE_TRACKS) || $(MAKE) -f Makefile.pipeline debris
	$(PYTHON) -m pipelines.animate --flow $(FLOW) --trajectories $(ANIMATE_TRACKS) --scene $(SCENE) \
	  --out $(ANIMATION)/$(basename $(notdir $(FLOW))).mp4 --gif $(ANIMATION)/$(basename $(notdir $(FLOW))).gif

## real-scale-qgis    runs/kainan-full/gis/project.qgz opened headless: the layer table, the checks, PNGs in runs/kainan-full/qgis
real-scale-qgis:
	$(call apt_install,real-scale-qgis,$(QGIS_PACKAGES))
	$(qgis_check) $(FULL)/gis/project.qgz --crs EPSG:32653 --png-dir $(FULL)/qgis --prefix kainan_full

## real-scale-animate the full-scale flow r00 with the sweep's bodies through it, MP4 and GIF in runs/kainan-full/animation
real-scale-animate: $(FULL)/sweep.nc
	$(PYTHON) -m pipelines.animate --flow $(firstword $(FULL_FLOWS)) --trajectories $(FULL)/sweep.nc --scene $(FULL)/scene.nc \
	  --out $(FULL)/animation/flow_r00.mp4 --gif $(FULL)/animation/flow_r00.gif
