# KITTI raw drives as Make rules: one rule per stage and per drive, so that `make -j` runs
# drives in parallel and reruns only what changed. Works on any folder laid out as KITTI raw
# ships it (<KITTI>/<date>/calib_*.txt and <KITTI>/<date>/<date>_drive_<n>_sync/).
#
#   make -j2 -f scripts/kitti.mk KITTI=/data/kitti_raw WORK=out/kitti
#   ... LAST_FRAME=29          # only frames 0..29 of every drive
#   ... DRIVES_GLOB='2011_09_26/*_drive_0005_sync'   # a subset
#
# Per drive <d> (the folder name):
#   $(WORK)/lidar/<d>/  lidar-semantic-map: map.ply, map.pcd, labels/, topdown.png, poses.txt
#                       (KITTI T_world_cam0; OXTS poses when the drive has oxts/, else LiDAR
#                       odometry), poses_velo.txt
#   $(WORK)/lsm/<d>/    lsm-build on image_02 with the poses.txt above:
#                       <d>.lsm.json, bird's-eye PNG, summary
# Each rule's target is the summary its tool writes last (tools write atomically), so a batch
# killed mid-way reruns only the unfinished drives.
#
# Variables: BIN (tools, default build/bin), CONFIG_DIR (folder with <stage>.json configs),
# MODEL (ENet Torch7 model; default: the tools' own default under ../shared), LAST_FRAME.

BIN ?= build/bin
WORK ?= out/kitti
DRIVES_GLOB ?= */*_drive_*_sync
LAST_FRAME ?= -1
CONFIG_DIR ?=
MODEL ?=
Q ?= -q

ifeq ($(KITTI),)
  $(error set KITTI=<folder holding <date>/<date>_drive_<n>_sync folders>)
endif
DRIVE_DIRS := $(sort $(patsubst %/image_02/,%,$(wildcard $(KITTI)/$(DRIVES_GLOB)/image_02/)))
ifeq ($(strip $(DRIVE_DIRS)),)
  $(error no KITTI raw drives with image_02/ under $(KITTI)/$(DRIVES_GLOB))
endif
DRIVES := $(notdir $(DRIVE_DIRS))

cfg = $(if $(CONFIG_DIR),$(if $(wildcard $(CONFIG_DIR)/$(1).json),--config $(CONFIG_DIR)/$(1).json))
model = $(if $(MODEL),--model $(MODEL))

LIDAR := $(foreach d,$(DRIVES),$(WORK)/lidar/$(d)/lidar-semantic-map.summary.json)
LSM := $(foreach d,$(DRIVES),$(WORK)/lsm/$(d)/lsm-build.summary.json)

.PHONY: all lidar lsm clean
all: $(LIDAR) $(LSM)
lidar: $(LIDAR)
lsm: $(LSM)

# $(1) = drive folder
define DRIVE_RULES
$(WORK)/lidar/$(notdir $(1))/lidar-semantic-map.summary.json: $(wildcard $(1)/velodyne_points/data/*.bin)
	$(BIN)/lidar-semantic-map $(Q) $(call cfg,lidar-semantic-map) $(model) --last-frame $(LAST_FRAME) -o $$(@D) $(1) >/dev/null

$(WORK)/lsm/$(notdir $(1))/lsm-build.summary.json: $(WORK)/lidar/$(notdir $(1))/lidar-semantic-map.summary.json
	$(BIN)/lsm-build $(Q) $(call cfg,lsm-build) $(model) --kitti-last-frame $(LAST_FRAME) --egomotion poses --poses $(WORK)/lidar/$(notdir $(1))/poses.txt -o $$(@D) $(1) >/dev/null
endef
$(foreach d,$(DRIVE_DIRS),$(eval $(call DRIVE_RULES,$(d))))

clean:
	rm -rf $(WORK)/lidar $(WORK)/lsm
