/* Fuzz target: the planner's plan file reader (hv_plan_parse, docs/PLAN_FORMAT.md).
 * Properties: no crash, leak or undefined behaviour; a refusal is one message naming the
 * file; an accepted plan written back (hv_plan_to_json) is read again, and writing that
 * gives the same text (what the reader accepts, the writer reproduces). */
#include <stdlib.h>
#include <string.h>

#include "fuzz_support.h"
#include "hv/plan_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hv_plan_t plan;
    char err[512] = "";
    hv_status_t st = hv_plan_parse((const char *)data, size, "in.json", &plan, err, sizeof err);
    if (st != HV_OK) {
        if (strncmp(err, "in.json", 7) != 0)
            hv_fuzz_fail("refused (%s) without naming the file: '%s'", hv_status_name(st), err);
        return 0;
    }
    char *text1 = NULL, *text2 = NULL;
    size_t len1 = 0, len2 = 0;
    if (hv_plan_to_json(&plan, &text1, &len1) != HV_OK)
        hv_fuzz_fail("an accepted plan cannot be written");
    hv_plan_free(&plan);
    st = hv_plan_parse(text1, len1, "out.json", &plan, err, sizeof err);
    if (st != HV_OK)
        hv_fuzz_fail("the writer's text of an accepted plan is refused: %s", err);
    if (hv_plan_to_json(&plan, &text2, &len2) != HV_OK)
        hv_fuzz_fail("a re-read plan cannot be written");
    if (len1 != len2 || memcmp(text1, text2, len1) != 0)
        hv_fuzz_fail("writing a plan read back from the writer's text changes it");
    hv_plan_free(&plan);
    free(text1);
    free(text2);
    return 0;
}
