/* The plan file's schema (plan_schema.h): the tables, in file order. */
#include "plan_schema.h"

#include "hv/plan.h"

/* A field's key and its member `m` of `type`. */
#define MEMBER(type, k, m) .key = k, .at = offsetof(type, m), .size = sizeof(((type *)0)->m)
#define COUNT(a)           (sizeof(a) / sizeof((a)[0]))
/* A nested object: its fields between braces. */
#define OBJECT(fields)     (&(const plan_object_t){fields, COUNT(fields), "{", "}"})

/* A new line before a top-level field, and before a stop's times and each arm's picks. */
#define TOP_LINE  ",\n  "
#define STOP_LINE ",\n     "

static const char *const k_methods[] = {"milp", "fov", "serial", NULL};
static const char *const k_pick_times[] = {"cycle", "one_way", "cycle_flat", "one_way_flat", NULL};
static const char *const k_statuses[] = {"optimal", "feasible",  "infeasible", "time_limit",
                                         "error",   "heuristic", NULL};

static const plan_field_t k_pick_fields[] = {
    {MEMBER(hv_plan_pick_t, "id", id), .kind = PLAN_ID},
    {MEMBER(hv_plan_pick_t, "x", x_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_pick_t, "y", y_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_pick_t, "z", z_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_pick_t, "yaw", yaw_rad), .kind = PLAN_NUM},
    {MEMBER(hv_plan_pick_t, "cost_s", cost_s), .kind = PLAN_NONNEG},
    {MEMBER(hv_plan_pick_t, "start_s", start_s), .kind = PLAN_NONNEG},
};
static const plan_array_t k_picks = {.element = OBJECT(k_pick_fields),
                                     .element_size = sizeof(hv_plan_pick_t),
                                     .first = "\n       ",
                                     .next = ",\n       ",
                                     .close = "]"};

static const plan_field_t k_stop_fields[] = {
    {MEMBER(hv_plan_stop_t, "index", index), .kind = PLAN_U32, .max = 4294967294.0},
    {MEMBER(hv_plan_stop_t, "y_m", y_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_stop_t, "pass", pass), .kind = PLAN_INT, .max = 1},
    {MEMBER(hv_plan_stop_t, "C_left_s", c_left_s), .kind = PLAN_NUM, .sep = STOP_LINE},
    {MEMBER(hv_plan_stop_t, "C_right_s", c_right_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_stop_t, "C_s", c_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_stop_t, "idle_left_s", idle_left_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_stop_t, "idle_right_s", idle_right_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_stop_t, "left", left), .kind = PLAN_ARRAY, .array = &k_picks,
     .count_at = offsetof(hv_plan_stop_t, n_left), .sep = STOP_LINE},
    {MEMBER(hv_plan_stop_t, "right", right), .kind = PLAN_ARRAY, .array = &k_picks,
     .count_at = offsetof(hv_plan_stop_t, n_right), .sep = STOP_LINE},
};
static const plan_array_t k_stops = {.element = OBJECT(k_stop_fields),
                                     .element_size = sizeof(hv_plan_stop_t),
                                     .first = "\n    ",
                                     .next = ",\n    ",
                                     .close = "\n  ]",
                                     .driving_order = 1};

static const plan_field_t k_unreachable_fields[] = {
    {MEMBER(hv_plan_unreachable_t, "id", id), .kind = PLAN_ID},
    {MEMBER(hv_plan_unreachable_t, "side", side), .kind = PLAN_SIDE},
    {MEMBER(hv_plan_unreachable_t, "reason", reason), .kind = PLAN_STR},
};
static const plan_array_t k_unreachables = {.element = OBJECT(k_unreachable_fields),
                                            .element_size = sizeof(hv_plan_unreachable_t),
                                            .first = "\n    ",
                                            .next = ",\n    ",
                                            .close = "\n  ]"};

static const plan_field_t k_inputs_fields[] = {
    {MEMBER(hv_plan_t, "fruit_map", fruit_map), .kind = PLAN_STR},
    {MEMBER(hv_plan_t, "cost_table_left", cost_table_left), .kind = PLAN_STR},
    {MEMBER(hv_plan_t, "cost_table_right", cost_table_right), .kind = PLAN_STR},
    {MEMBER(hv_plan_t, "config", config), .kind = PLAN_STR},
};

static const plan_field_t k_params_fields[] = {
    {MEMBER(hv_plan_t, "stop_step_m", stop_step_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "row_start_m", row_start_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "row_length_m", row_length_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "stop_penalty_s", stop_penalty_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "vehicle_speed_mps", vehicle_speed_mps), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "travel_time_s", travel_time_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "stop_margin_m", stop_margin_m), .kind = PLAN_NONNEG},
    {MEMBER(hv_plan_t, "pick_time", pick_time), .kind = PLAN_STR, .values = k_pick_times,
     .refusal = "expected cycle, one_way, cycle_flat or one_way_flat, got"},
};

static const plan_field_t k_solver_fields[] = {
    {MEMBER(hv_plan_t, "status", solver_status), .kind = PLAN_STR, .values = k_statuses,
     .refusal = "unknown status"},
    {MEMBER(hv_plan_t, "gap", gap), .kind = PLAN_GAP},
    {MEMBER(hv_plan_t, "nodes", nodes), .kind = PLAN_LONG, .max = 9e15},
    {MEMBER(hv_plan_t, "runtime_s", runtime_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "time_limit_s", time_limit_s), .kind = PLAN_NUM},
};

static const plan_field_t k_totals_fields[] = {
    {MEMBER(hv_plan_t, "makespan_s", makespan_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "pick_time_s", pick_time_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "stop_time_s", stop_time_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "travel_time_s", total_travel_time_s), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "stops", n_stops_total), .kind = PLAN_SIZE, .max = 4e9},
    {MEMBER(hv_plan_t, "fruits_planned", fruits_planned), .kind = PLAN_SIZE, .max = 4e9},
    {MEMBER(hv_plan_t, "fruits_unreachable", fruits_unreachable), .kind = PLAN_SIZE, .max = 4e9},
    {MEMBER(hv_plan_t, "throughput_fruit_per_s", throughput_fruit_per_s), .kind = PLAN_NUM},
};

static const plan_field_t k_horizon_fields[] = {
    {MEMBER(hv_plan_t, "window_m", horizon.window_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "commit_m", horizon.commit_m), .kind = PLAN_NUM},
    {MEMBER(hv_plan_t, "windows", horizon.windows), .kind = PLAN_U32, .max = 4e9},
    {MEMBER(hv_plan_t, "windows_optimal", horizon.windows_optimal), .kind = PLAN_U32, .max = 4e9},
};

static const plan_field_t k_plan_fields[] = {
    {.key = "format", .kind = PLAN_FORMAT},
    {.key = "version", .kind = PLAN_VERSION, .max = 1e9},
    {MEMBER(hv_plan_t, "method", method), .kind = PLAN_STR, .values = k_methods,
     .refusal = "expected milp, fov or serial, got", .sep = TOP_LINE},
    {.key = "inputs", .kind = PLAN_OBJECT, .object = OBJECT(k_inputs_fields), .sep = TOP_LINE},
    {.key = "params", .kind = PLAN_OBJECT, .object = OBJECT(k_params_fields), .sep = TOP_LINE},
    {.key = "solver", .kind = PLAN_OBJECT, .object = OBJECT(k_solver_fields), .sep = TOP_LINE},
    {.key = "totals", .kind = PLAN_OBJECT, .object = OBJECT(k_totals_fields), .sep = TOP_LINE},
    {MEMBER(hv_plan_t, "horizon", horizon.used), .kind = PLAN_OBJECT,
     .object = OBJECT(k_horizon_fields), .optional = 1, .sep = TOP_LINE},
    {MEMBER(hv_plan_t, "stops", stops), .kind = PLAN_ARRAY, .array = &k_stops,
     .count_at = offsetof(hv_plan_t, n_stops), .sep = TOP_LINE},
    {MEMBER(hv_plan_t, "unreachable", unreachable), .kind = PLAN_ARRAY, .array = &k_unreachables,
     .count_at = offsetof(hv_plan_t, n_unreachable), .sep = TOP_LINE},
};

const plan_object_t plan_schema = {k_plan_fields, COUNT(k_plan_fields), "{\n  ", "\n}\n"};
