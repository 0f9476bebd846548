/* The plan image: a prepared plan (hv/exec_plan.h, IK already solved by the host) and the
 * executor's parameters as the firmware receives them over the bus (DBC ExecutorPlanBegin /
 * ExecutorPlanData, CRC-32 over the whole image). Little-endian, fixed-size records, so the
 * firmware decodes each record as it completes and never buffers the image:
 *
 *   header  HV_FW_IMAGE_HEADER bytes: u32 magic "HVFW", u16 version, u16 n_stops,
 *           u16 n_picks, u8 max_retries, u8 clear_estop, then f64: time_scale, margin,
 *           slack_s, latency_s, heartbeat_timeout_s, heartbeat_period_s, startup_timeout_s,
 *           command_timeout_s, home_max_s, cut_s, release_s, vehicle_speed_mps,
 *           vehicle_accel_mps2, resend_s (hv_exec_params_t), row_start_m, row_length_m,
 *           stop_margin_m, planned_makespan_s, planned_pick_s, final_drive_s,
 *           expected_makespan_s, home[2][4] (hv_exec_plan_t)
 *   n_stops x HV_FW_IMAGE_STOP bytes: u32 plan_index, u16 first[2], u16 count[2], f64 y_m,
 *           arm_s[2], expected_s, drive_s
 *   n_picks x HV_FW_IMAGE_PICK bytes: u8 side, u8 reachable, u16 stop, char id[32]
 *           (NUL-padded), f64 q[4], move_s, cycle_s, cost_s, start_s, x_m, y_m, z_m, yaw_rad
 *
 * Pure code: the host's writer (harvest-fw-plan) and the firmware's reader share it. */
#ifndef HV_FW_PLAN_IMAGE_H
#define HV_FW_PLAN_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/exec_sm.h"

#define HV_FW_IMAGE_MAGIC      0x57465648u /* "HVFW" */
#define HV_FW_IMAGE_VERSION    1u
#define HV_FW_IMAGE_HEADER     (12u + 29u * 8u)
#define HV_FW_IMAGE_STOP       (12u + 5u * 8u)
#define HV_FW_IMAGE_PICK       (36u + 12u * 8u)
#define HV_FW_IMAGE_RECORD_MAX HV_FW_IMAGE_HEADER

/* Bytes of the image of a plan with these counts. */
size_t hv_fw_image_size(unsigned n_stops, unsigned n_picks);

/* Host: the image of a prepared plan and its parameters into buf (len >= its size);
 * returns the bytes written, 0 when buf is too small. */
size_t hv_fw_image_write(const hv_exec_plan_t *plan, const hv_exec_params_t *prm, uint8_t *buf,
                         size_t len);

/* Firmware: the image decoded as it arrives, record by record. */
typedef struct hv_fw_image_reader {
    hv_exec_plan_t *plan; /* filled as records complete */
    hv_exec_params_t *prm;
    uint32_t total, crc_want; /* from ExecutorPlanBegin */
    uint32_t received;        /* bytes so far */
    uint32_t crc;             /* CRC-32 of what arrived */
    unsigned record;          /* records done: 0 header, then stops, then picks */
    unsigned fill;            /* bytes of the record under way */
    uint8_t buf[HV_FW_IMAGE_RECORD_MAX];
} hv_fw_image_reader_t;

/* Start an upload of `total` bytes with CRC-32 `crc` into plan and prm. */
void hv_fw_image_begin(hv_fw_image_reader_t *r, hv_exec_plan_t *plan, hv_exec_params_t *prm,
                       uint32_t total, uint32_t crc);

/* The next bytes at `offset`. HV_OK, or HV_ERR_FW_UPLOAD_ORDER (offset is not where the
 * image stands), HV_ERR_FW_UPLOAD_LENGTH (more than announced, or the header's counts
 * disagree with it), HV_ERR_FW_UPLOAD_FORMAT (a record out of range: magic, version,
 * capacity, a stop's picks, a pick's side/stop/id, a number not finite). */
hv_status_t hv_fw_image_data(hv_fw_image_reader_t *r, uint32_t offset, const uint8_t *data,
                             size_t n);

/* 1 once every announced byte arrived. */
int hv_fw_image_complete(const hv_fw_image_reader_t *r);

/* After the last byte: HV_OK when the CRC-32 matches (the plan and parameters are then
 * whole), HV_ERR_FW_UPLOAD_CRC otherwise, HV_ERR_FW_UPLOAD_LENGTH when bytes are missing. */
hv_status_t hv_fw_image_finish(const hv_fw_image_reader_t *r);

#endif /* HV_FW_PLAN_IMAGE_H */
