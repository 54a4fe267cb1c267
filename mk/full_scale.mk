# Kainan at the prototype scale: GIS in, the same physics x250, GIS out (docs/gis.md).
#
# The shared DEM x250 as a GeoTIFF in UTM zone 53N (EPSG:32653), the flume's x = y = 0 at
# E 518000, N 3780000 (34.16 N, 135.195 E), its values in a vertical datum 0.9 m below
# still water (gdal_translate -scale maps 0..1 m to 0.9..250.9 m: z x 250 + 0.9); building
# footprints derived from its roofs (the flume's building rule x250, gdal_polygonize) and
# read back as a vector file; Froude-scaled WG1 records; flows, the sweep of
# sweep/examples/kainan_full_scale.toml, statistics, GeoTIFF maps and the chart. The data
# is made at run time under runs/kainan-full/, never committed.

##@ Full scale (docs/gis.md)
## FULL_RES     grid of the full-scale scene [m] (10)
## FULL_COUNT   full-scale flows (4)
FULL          ?= $(RUNS)/kainan-full
FULL_RES      ?= 10
FULL_COUNT    ?= 4
FULL_DATUM    := 0.9
FULL_ULLR     := 514908.75 3779998.75 520001.25 3778998.75
FULL_DURATION := 6640
FULL_FEATURES := data/examples/kainan_full_scale.toml
FULL_SPEC     := sweep/examples/kainan_full_scale.toml
FULL_FLOWS    := $(foreach r,$(shell seq -f '%02g' 0 $$(( $(FULL_COUNT) - 1 ))),$(FULL)/flows/flow_r$(r).nc)
FULL_BCS      := $(patsubst $(FULL)/flows/flow_r%.nc,$(FULL)/bc/wg1_r%.csv,$(FULL_FLOWS))

.PHONY: real-scale-demo real-scale-scene real-scale-flows real-scale-maps real-scale-nested

# The inputs a port would hand over (a DSM, roof footprints) live in input/, apart from
# what flotsam writes.
$(FULL)/input/kainan_dsm.tif: $(REAL_DEM) | tool
	@mkdir -p $(@D)
	gdal_translate -q -of GTiff -ot Float32 -a_srs EPSG:32653 -a_ullr $(FULL_ULLR) -scale 0 1 0.9 250.9 -a_nodata none \
	  -co COMPRESS=DEFLATE -co PREDICTOR=3 -co TILED=YES NETCDF:"$(REAL_DEM)":z $@

$(FULL)/input/roof_footprints.gpkg: $(FULL)/input/kainan_dsm.tif data/examples/kainan_full_scale_buildings.toml
	$(FLOTSAM) scene import --dem $< --still-water-level $(FULL_DATUM) \
	  --features data/examples/kainan_full_scale_buildings.toml --resolution 2.5 --out $(@D)/roofs.nc
	gdal_translate -q -a_nodata 0 NETCDF:"$(@D)/roofs.nc":building $(@D)/roofs.tif
	rm -f $@ && gdal_polygonize.py -q $(@D)/roofs.tif -f GPKG $@ roofs
	rm -f $(@D)/roofs.nc $(@D)/roofs.tif

$(FULL)/scene.nc: $(FULL)/input/kainan_dsm.tif $(FULL)/input/roof_footprints.gpkg $(FULL_FEATURES)
	$(FLOTSAM) scene import --dem $< --still-water-level $(FULL_DATUM) --features $(FULL_FEATURES) \
	  --buildings $(FULL)/input/roof_footprints.gpkg --resolution $(FULL_RES) --out $@

$(FULL_BCS) &: | tool
	$(FLOTSAM) boundary generate --out-dir $(FULL)/bc --count $(FULL_COUNT) --seed $(SEED) --duration 420 \
	  --froude-scale 250

# The scene recommends its max-dt, dry depth, frame and gauge intervals, output window,
# nesting interface and arrival depth ([hydro] in $(FULL_FEATURES)).
$(FULL)/flows/flow_r%.nc: $(FULL)/bc/wg1_r%.csv $(FULL)/scene.nc | tool
	$(FLOTSAM) hydro --scene $(FULL)/scene.nc --west level --west-series $< --realisation $$((10#$*)) \
	  --duration $(FULL_DURATION) --threads $(THREADS) --label "full-scale r$*" --out $@

# The port's debris sources: a container yard and a car park as GeoPackage layers in the
# port's survey CRS (EPSG:6674), read by the spec's [[sources]].
$(FULL)/port_layers.gpkg: pipelines/port_layers.py
	@mkdir -p $(@D)
	$(PYTHON) -m pipelines.port_layers --out $@

$(FULL)/sweep.nc: $(FULL_FLOWS) $(FULL_SPEC) $(FULL)/port_layers.gpkg | tool
	$(FLOTSAM) sweep --spec $(FULL_SPEC) --scene $(FULL)/scene.nc $(foreach f,$(FULL_FLOWS),--flow $(f)) \
	  --threads $(JOBS) --out $@

# Region counts at the flume's 300 s and yaw over its 30 s, x sqrt(250).
$(FULL)/stats.nc: $(FULL)/sweep.nc
	$(FLOTSAM) stats --sweep $< --scene $(FULL)/scene.nc --arrival-time 4743 --yaw-window 474 --out $@ \
	  --csv $(FULL)/stats_csv

## real-scale-scene  the GeoTIFF, the footprints and the full-scale scene
real-scale-scene: $(FULL)/scene.nc
## real-scale-flows  the full-scale flows
real-scale-flows: $(FULL_FLOWS)
## real-scale-maps   sweep, statistics, hazard regions, the GIS export (COG maps, GeoPackages, QGIS project), charts
real-scale-maps: $(FULL)/stats.nc
	$(PYTHON) -m pipelines.hazard_region --sweep $(FULL)/sweep.nc --scene $(FULL)/scene.nc --out $(FULL)/hazard
	$(FLOTSAM) export --stats $(FULL)/stats.nc --scene $(FULL)/scene.nc $(foreach f,$(FULL_FLOWS),--flow $(f)) \
	  --trajectories $(FULL)/sweep.nc --sources $(FULL)/port_layers.gpkg --hazard-regions $(FULL)/hazard/hazard_regions.nc \
	  --out-dir $(FULL)/gis
	$(PYTHON) -m pipelines.charts --scene $(FULL)/scene.nc --stats $(FULL)/stats.nc --out $(FULL)/charts --only-buildings
	gdalinfo $(FULL)/gis/pass_probability_all.tif | grep -E "^(Size|Origin|Pixel Size)|LAYOUT|ID\[\"EPSG\",32653\]\]$$"
	$(PYTHON) -m pipelines.charts_full_scale --scene $(FULL)/scene.nc --stats $(FULL)/stats.nc --sweep $(FULL)/sweep.nc \
	  --flows $(FULL_FLOWS) --out $(FULL)/kainan_full_scale.png

# Forcing from a regional model, in two steps (docs/gis.md): a regional run of the whole
# area at 20 m writes the level and velocity on the outline of the port box; the outline
# is rewritten in longitude and latitude (as a regional model in geographic coordinates
# gives it); a 10 m run of the port box alone is driven through its west and south sides
# by it, and compared with the 10 m run of the whole area (flow_r00).
FULL_BOX := 517748.75,520001.25,3779128.75,3779998.75
$(FULL)/regional/scene.nc: $(FULL)/input/kainan_dsm.tif $(FULL)/input/roof_footprints.gpkg $(FULL_FEATURES)
	@mkdir -p $(@D)
	$(FLOTSAM) scene import --dem $< --still-water-level $(FULL_DATUM) --features $(FULL_FEATURES) \
	  --buildings $(FULL)/input/roof_footprints.gpkg --resolution 20 --out $@
$(FULL)/regional/outline.nc: $(FULL)/regional/scene.nc $(FULL)/bc/wg1_r00.csv | tool
	$(FLOTSAM) hydro --scene $< --west level --west-series $(FULL)/bc/wg1_r00.csv --duration $(FULL_DURATION) \
	  --boundary-output $@ --boundary-box $(FULL_BOX) --boundary-interval 10 --threads $(THREADS) --label "regional 20 m" \
	  --out $(FULL)/regional/flow_r00.nc
$(FULL)/regional/outline_lonlat.nc: $(FULL)/regional/outline.nc
	$(PYTHON) -m pipelines.boundary_files to-lonlat $< $@
$(FULL)/port/scene.nc: $(FULL)/input/kainan_dsm.tif $(FULL)/input/roof_footprints.gpkg $(FULL_FEATURES)
	@mkdir -p $(@D)
	$(FLOTSAM) scene import --dem $< --still-water-level $(FULL_DATUM) --features $(FULL_FEATURES) \
	  --buildings $(FULL)/input/roof_footprints.gpkg --resolution $(FULL_RES) --extent $(FULL_BOX) --out $@
$(FULL)/port/flow_r00.nc: $(FULL)/port/scene.nc $(FULL)/regional/outline_lonlat.nc | tool
	$(FLOTSAM) hydro --scene $< --west-forcing $(FULL)/regional/outline_lonlat.nc \
	  --south-forcing $(FULL)/regional/outline_lonlat.nc --nest-ratio 1 --duration $(FULL_DURATION) --threads $(THREADS) \
	  --label "port 10 m" --out $@

## real-scale-nested the two-step workflow: a regional run drives the port box (runs/kainan-full/port/)
real-scale-nested: $(FULL)/port/flow_r00.nc $(FULL)/flows/flow_r00.nc
	$(PYTHON) -m pipelines.flow_error --box $(FULL_BOX) $(FULL)/scene.nc $(FULL)/flows/flow_r00.nc \
	  $(FULL)/regional/flow_r00.nc $(FULL)/port/flow_r00.nc | tee $(FULL)/port/nesting_error.csv
	$(PYTHON) -m pipelines.nesting_check $(FULL)/port/nesting_error.csv $(FULL)/flows/flow_r00.nc --time-scale 15.811

## real-scale-demo   install what is missing, then all of the above (runs/kainan-full/)
real-scale-demo: setup
	@start=$$(date +%s); \
	$(MAKE) -f Makefile.pipeline real-scale-scene $(FULL_BCS) && \
	$(MAKE) -f Makefile.pipeline -j$(JOBS) real-scale-flows && \
	$(MAKE) -f Makefile.pipeline real-scale-maps && \
	$(MAKE) -f Makefile.pipeline real-scale-animate && \
	$(MAKE) -f Makefile.pipeline real-scale-nested && \
	echo "real-scale-demo: done in $$(( $$(date +%s) - start )) s: the QGIS project $(FULL)/gis/project.qgz (GeoTIFFs, GeoPackages), hazard regions in $(FULL)/hazard, chart $(FULL)/kainan_full_scale.png, animation in $(FULL)/animation"
