# Crowdsourced vector-map pipeline as Make rules: one rule per stage and per drive, so that
# `make -j` runs independent drives in parallel and reruns only what changed. Every tool writes
# its outputs atomically and each rule's target is the file its tool writes last, so a batch
# killed mid-way reruns only the unfinished steps.
#
#   make -j2 -f scripts/crowd.mk LSM_DIR=drives/ WORK=out/crowd            # LSMs as input
#   make -j2 -f scripts/crowd.mk FRAMES_DIR=frames/ WORK=out/crowd         # raw drives as input
#   ... TRUTH=truth/vector_map.json TRUTH_TRAJ=truth/   # adds evaluate
#   ... TILE_SIZE=500                          # align per tile, balance, aggregate per tile, stitch
#   ... MAX_UNTRUSTED_SHARE=0.1   # the trust check (check.json) fails above this share (default 0)
#   make -j2 -f scripts/crowd.mk UPDATE_MAP=out/crowd/aggregate/map.json LSM_DIR=new/ WORK=out/upd
#                                  # map update: the drives of LSM_DIR / FRAMES_DIR are the new
#                                  # ones, georeferenced in the map's frame (docs/update.md)
#
# Variables: BIN (tools, default build/bin), METHOD (align method, default gba_sgicp),
# CONFIG_DIR (folder with <stage>.json configs; default: none, built-in defaults),
# ORIGIN (lat,lon,alt; default: derived once from the first drive's first GPS fix).

CROWD_MK_DIR := $(dir $(lastword $(MAKEFILE_LIST)))
BIN ?= build/bin
WORK ?= out/crowd
METHOD ?= gba_sgicp
TRUTH ?=
TRUTH_TRAJ ?=
TILE_SIZE ?=
TILE_MARGIN ?= 50
CONFIG_DIR ?=
UPDATE_MAP ?=
Q ?= -q

cfg = $(if $(CONFIG_DIR),$(if $(wildcard $(CONFIG_DIR)/$(1).json),--config $(CONFIG_DIR)/$(1).json))

ifneq ($(FRAMES_DIR),)
  # Raw drives: one folder per drive holding frames.json; lsm-build makes <drive>.lsm.json.
  DRIVES := $(sort $(notdir $(patsubst %/frames.json,%,$(wildcard $(FRAMES_DIR)/*/frames.json))))
  LSMS := $(foreach d,$(DRIVES),$(WORK)/lsm/$(d).lsm.json)
else ifneq ($(LSM_DIR),)
  LSMS := $(sort $(wildcard $(LSM_DIR)/*.cbor $(LSM_DIR)/*.json))
else
  $(error set LSM_DIR=<folder of LSM files> or FRAMES_DIR=<folder of raw drive folders>)
endif
ifeq ($(strip $(LSMS)),)
  $(error no drives found (LSM_DIR=$(LSM_DIR) FRAMES_DIR=$(FRAMES_DIR)))
endif

NAMES := $(notdir $(LSMS))
GEOREF := $(foreach n,$(NAMES),$(WORK)/georef/$(n).d/$(n))
GEOREF_DONE := $(foreach n,$(NAMES),$(WORK)/georef/$(n).d/georef.summary.json)
ALIGN_SUMMARY := $(WORK)/align/align.summary.json
ALIGNED := $(foreach n,$(NAMES),$(WORK)/align/$(n))
MAP_SUMMARY := $(WORK)/aggregate/aggregate.summary.json
MAP := $(WORK)/aggregate/map.cbor
ifneq ($(TILE_SIZE),)
  MAP_SUMMARY := $(WORK)/stitch/stitch.summary.json
  MAP := $(WORK)/stitch/map.cbor
endif
EVAL_SUMMARY := $(WORK)/evaluate/evaluate.summary.json
CHECK := $(WORK)/check.json
MAX_UNTRUSTED_SHARE ?= 0
UPDATE_SUMMARY := $(WORK)/update/update.summary.json

.PHONY: all map evaluate check update clean
ifneq ($(UPDATE_MAP),)
all: $(UPDATE_SUMMARY)
else
all: $(if $(TRUTH),$(EVAL_SUMMARY),$(MAP_SUMMARY)) $(CHECK)
endif
check: $(CHECK)
map: $(MAP_SUMMARY)
evaluate: $(EVAL_SUMMARY)

# ---- lsm-build: one rule per raw drive ----
define LSM_BUILD_RULE
$(WORK)/lsm/$(1).lsm.json: $(FRAMES_DIR)/$(1)/frames.json
	$(BIN)/lsm-build $(Q) $(call cfg,lsm-build) -o $(WORK)/lsm/$(1).d $(FRAMES_DIR)/$(1) >/dev/null
	mv $(WORK)/lsm/$(1).d/$(1).lsm.json $$@
endef
$(foreach d,$(DRIVES),$(eval $(call LSM_BUILD_RULE,$(d))))

# ---- the batch's one ENU origin, derived once (a map update: the map's) ----
ORIGIN_SOURCE := $(if $(UPDATE_MAP),$(UPDATE_MAP),$(firstword $(LSMS)))
$(WORK)/origin.txt: | $(ORIGIN_SOURCE)
	@mkdir -p $(WORK)
	$(if $(ORIGIN),echo $(ORIGIN),$(BIN)/info --origin $(ORIGIN_SOURCE)) > $@.tmp && mv $@.tmp $@

# ---- georef: one rule per drive, all sharing origin.txt ----
define GEOREF_RULE
$(WORK)/georef/$(notdir $(1)).d/georef.summary.json: $(1) $(WORK)/origin.txt
	$(BIN)/georef $(Q) $(call cfg,georef) --origin $$(file <$(WORK)/origin.txt) -o $(WORK)/georef/$(notdir $(1)).d $(1)
endef
$(foreach l,$(LSMS),$(eval $(call GEOREF_RULE,$(l))))

ifeq ($(TILE_SIZE),)
# ---- align: all drives together; its summary is written last ----
$(ALIGN_SUMMARY): $(GEOREF_DONE)
	$(BIN)/align $(Q) $(call cfg,align) --method $(METHOD) -o $(WORK)/align $(GEOREF)

# ---- aggregate ----
$(MAP_SUMMARY): $(ALIGN_SUMMARY)
	$(BIN)/aggregate $(Q) $(call cfg,aggregate) -o $(WORK)/aggregate $(ALIGNED)
else
# ---- tiled: tile; align per tile; balance (one step over all tiles: places every tile's
# registration groups consistently); aggregate per tile; stitch. Per-tile steps run in sub-makes
# over the tile list, which exists only once `tile` has run. ----
BALANCE_SUMMARY := $(WORK)/balance/balance.summary.json
$(WORK)/tiles/tiles.txt: $(GEOREF_DONE)
	@mkdir -p $(WORK)/tiles
	$(BIN)/tile $(Q) $(call cfg,tile) --tile-size $(TILE_SIZE) --margin $(TILE_MARGIN) -o $(WORK)/tiles $(GEOREF) > $@.tmp && mv $@.tmp $@

$(BALANCE_SUMMARY): $(WORK)/tiles/tiles.txt
	$(MAKE) -f $(lastword $(MAKEFILE_LIST)) tiles-align TILES="$$(cat $<)"
	$(BIN)/balance $(Q) $(call cfg,balance) --tiles $(WORK)/tiles/tiles.json -o $(WORK)/balance >/dev/null

$(MAP_SUMMARY): $(BALANCE_SUMMARY)
	$(MAKE) -f $(lastword $(MAKEFILE_LIST)) tiles-aggregate TILES="$$(cat $(WORK)/tiles/tiles.txt)"
	$(BIN)/stitch $(Q) $(call cfg,stitch) --tiles $(WORK)/tiles/tiles.json -o $(MAP) \
	  $$(sed 's|.*|$(WORK)/tiles/&/aggregate/map.cbor|' $(WORK)/tiles/tiles.txt)
endif

# Per-tile align summaries are intermediate files of pattern rules: keep them (and everything
# else) so that a rerun does not redo finished tiles. Output LSMs are named like the tile's
# inputs (a $(wildcard) of an output folder would see make's stale directory cache).
.SECONDARY:
.PHONY: tiles-align tiles-aggregate
tile_inputs = $(wildcard $(WORK)/tiles/$(1)/*.cbor $(WORK)/tiles/$(1)/*.json)
tiles-align: $(foreach t,$(TILES),$(WORK)/tiles/$(t)/align/align.summary.json)
tiles-aggregate: $(foreach t,$(TILES),$(WORK)/tiles/$(t)/aggregate/aggregate.summary.json)
$(WORK)/tiles/%/align/align.summary.json:
	$(BIN)/align $(Q) $(call cfg,align) --method $(METHOD) -o $(WORK)/tiles/$*/align $(call tile_inputs,$*)
$(WORK)/tiles/%/aggregate/aggregate.summary.json: $(WORK)/balance/balance.summary.json
	$(BIN)/aggregate $(Q) $(call cfg,aggregate) -o $(WORK)/tiles/$*/aggregate $(patsubst $(WORK)/tiles/$*/%,$(WORK)/balance/$*/%,$(call tile_inputs,$*))

# ---- evaluate against ground truth (trajectory metrics untiled only: a tiled run has no single
# aligned copy of each drive) ----
$(EVAL_SUMMARY): $(MAP_SUMMARY) $(TRUTH)
	$(BIN)/evaluate map $(Q) --map $(MAP) --truth $(TRUTH) $(if $(TRUTH_TRAJ),--truth-trajectories $(TRUTH_TRAJ) $(if $(TILE_SIZE),,--lsm $(ALIGNED))) -o $(WORK)/evaluate

# ---- trust check of the batch (issue 33): drives whose odometry and GPS disagree are named;
# above MAX_UNTRUSTED_SHARE the check exits 3 (make then stops with "Error 3") ----
$(CHECK): $(MAP_SUMMARY)
	python3 $(CROWD_MK_DIR)crowd_check.py $(WORK) --max-untrusted-share $(MAX_UNTRUSTED_SHARE)

# ---- map update (issue 34): the new drives, georeferenced in the map's frame, against the map;
# outputs replaced as a set, so a killed update leaves the previous WORK/update as it was ----
update: $(UPDATE_SUMMARY)
$(UPDATE_SUMMARY): $(GEOREF_DONE) $(UPDATE_MAP)
	$(if $(UPDATE_MAP),,$(error set UPDATE_MAP=<the existing map> for the update target))
	$(BIN)/update $(Q) $(call cfg,update) --map $(UPDATE_MAP) -o $(WORK)/update $(GEOREF)

clean:
	rm -rf $(WORK)
