# Debian packages: one install macro, used by `setup` and by `fuzz-build`.

DEB_PACKAGES := cmake g++ make pkg-config git libeigen3-dev libhdf5-dev libnetcdf-dev libcli11-dev libdeflate-dev \
                libgtest-dev googletest netcdf-bin python3-matplotlib python3-xarray python3-netcdf4 \
                python3-numpy cdo libgdal-dev gdal-bin python3-gdal ffmpeg

# $(call apt_install,WHO,PACKAGES): installs those of PACKAGES that are missing (as root, or
# through sudo), saying "WHO: installing ..."; prints OTHERWISE when all are present.
define apt_install
@missing=""; for p in $(2); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
if [ -n "$$missing" ]; then \
  echo "$(1): installing$$missing"; \
  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
$(if $(3),else echo "$(1): $(3)"; )fi
endef

.PHONY: setup
##@ Set-up
## setup        install the Debian packages that are missing (as root or through sudo)
setup:
	$(call apt_install,setup,$(DEB_PACKAGES),all Debian packages present)

# The README's commands install what is missing before anything is compiled; a plain
# `build` or stage target does not.
ifneq ($(filter test demo real-scale-demo,$(MAKECMDGOALS)),)
$(BUILD)/Makefile build tool: | setup
endif
