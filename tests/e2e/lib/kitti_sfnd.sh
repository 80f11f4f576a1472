# Sourced by the e2e scripts on the real KITTI sfnd drive: sets BIN, SHARED, DATE, DRIVE (the
# sfnd drive), MODEL (ENet) and TMP (a scratch folder removed on exit, the working folder), or
# skips (exit 77) when the shared data or the model is absent.
SHARED="${MAPFUSE_SHARED:-${MAPFUSE_SOURCE_DIR:?}/../shared}"
DATE="$SHARED/data/kitti_raw/2011_09_26"
DRIVE="$DATE/2011_09_26_drive_sfnd_sync"
MODEL="$SHARED/models/enet-cityscapes/enet-model.net"
if [[ ! -d "$DRIVE" || ! -f "$MODEL" ]]; then echo "SKIP: shared data absent ($DRIVE)"; exit 77; fi
source "$(dirname "${BASH_SOURCE[0]}")/scratch.sh"  # BIN; TMP, the working folder
