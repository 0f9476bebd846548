/* Status codes shared by every C module of the harvest stack.
 *
 * Every public function returns hv_status_t: HV_OK (0) or a named negative code.
 * Ranges are reserved per module so a code alone says where it came from:
 *   -1..-99     core (arguments, kinematics, config, cost table)
 *   -100..-199  planner
 *   -200..-299  executor
 *   -300..-399  CAN protocol and transports
 *   -400..-499  firmware (board, UART, SLCAN; firmware/fw_status.h)
 */
#ifndef HV_STATUS_H
#define HV_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hv_status {
    HV_OK = 0,

    /* generic */
    HV_ERR_ARG = -1,      /* NULL pointer or argument outside its documented domain */
    HV_ERR_NAN = -2,      /* a NaN or infinite number where a finite one is required */
    HV_ERR_NOMEM = -3,    /* caller-supplied buffer too small (core never allocates) */
    HV_ERR_IO = -4,       /* file could not be opened, read or written (io helpers only) */
    HV_ERR_FRUIT_ID = -5, /* a fruit id outside the allowed set (hv/fruit_id.h) */

    /* kinematics */
    HV_ERR_UNREACHABLE = -10, /* pose outside the arm's workspace */
    HV_ERR_JOINT_LIMIT = -11, /* an IK solution exists but violates a joint limit */

    /* cost table file */
    HV_ERR_TAB_TRUNCATED = -20, /* buffer shorter than the header or header+payload */
    HV_ERR_TAB_MAGIC = -21,
    HV_ERR_TAB_VERSION = -22,
    HV_ERR_TAB_HEADER = -23,   /* header size or a header field is inconsistent */
    HV_ERR_TAB_GRID = -24,     /* grid axis invalid, or payload size != cells * 2 */
    HV_ERR_TAB_CRC = -25,      /* payload or header CRC-32 mismatch */
    HV_ERR_TAB_MISMATCH = -26, /* table valid but built for another arm/grid than expected */
    HV_ERR_OUT_OF_GRID = -27,  /* lookup pose outside the table grid (treated as unreachable) */

    /* configuration text */
    HV_ERR_CFG_SYNTAX = -30,  /* a line is not `key = value` or a value does not parse */
    HV_ERR_CFG_UNKNOWN = -31, /* unknown key (never silently ignored) */
    HV_ERR_CFG_MISSING = -32, /* a required key is absent */
    HV_ERR_CFG_RANGE = -33,   /* a value is outside its allowed range */
    HV_ERR_CFG_DUPLICATE = -34,

    /* not a code: keeps hv_status_t as wide as an int where the ABI sizes an enum by its
     * values (arm-none-eabi: 1 byte for -34..0), since the other modules' codes down to
     * -499 are cast to it */
    HV_STATUS_INT_WIDTH_ = -0x7FFFFFFF
} hv_status_t;

/* Short, stable, human-readable name of a status code ("HV_ERR_TAB_CRC"). Never NULL. */
const char *hv_status_name(int status);

/* Diagnostics filled by functions that parse or validate input: the field or key at
 * fault and a one-line explanation. Callers add the file name when printing. */
typedef struct hv_diag {
    char field[48];    /* e.g. "grid.y.count", "joint3.max", "payload_crc32" */
    char message[160]; /* e.g. "expected 1203 cells * 2 bytes, file has 1000" */
    int line;          /* 1-based line for text input, 0 when not applicable */
} hv_diag_t;

#ifdef __cplusplus
}
#endif
#endif /* HV_STATUS_H */
