/* Without libFuzzer (a gcc build): run a fuzz target once on every file of the corpus
 * folders (or files) given, so the corpora (seeds, crafted bad inputs, the reproducers of
 * fixed crashes) are regression tests in every build; in the test build (build-test/,
 * ASan + UBSan, halt_on_error) a sanitizer report fails the replay. Usage: fuzz_<target> CORPUS_DIR|FILE ... */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_support.h"
#include "hv/file_io.h"

static int run_file(const char *path)
{
    void *data;
    size_t len;
    char err[512];
    if (hv_file_read_all(path, &data, &len, err, sizeof err) != HV_OK) {
        fprintf(stderr, "replay: %s\n", err);
        return -1;
    }
    /* an exact-size copy: the reader's buffer ends in a NUL the target must not lean on,
     * and ASan sees a read one byte past the input only when nothing is there */
    uint8_t *exact = malloc(len ? len : 1);
    if (!exact) {
        free(data);
        fprintf(stderr, "replay: %s: out of memory\n", path);
        return -1;
    }
    memcpy(exact, data, len);
    free(data);
    LLVMFuzzerTestOneInput(exact, len);
    free(exact);
    return 1;
}

static int filter_hidden(const struct dirent *d)
{
    return d->d_name[0] != '.';
}

/* Every file of a folder, in name order; the number run, -1 on an error. */
static int run_dir(const char *dir)
{
    struct dirent **names;
    int n = scandir(dir, &names, filter_hidden, alphasort);
    if (n < 0) {
        perror(dir);
        return -1;
    }
    int done = 0;
    for (int i = 0; i < n; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]->d_name);
        free(names[i]);
        if (done >= 0)
            done = run_file(path) < 0 ? -1 : done + 1;
    }
    free(names);
    return done;
}

int main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fprintf(stderr,
                "usage: %s CORPUS_DIR|FILE ...\n"
                "Runs the fuzz target once on each input (the build without "
                "libFuzzer).\n",
                argv[0]);
        return argc < 2 ? 2 : 0;
    }
    for (int i = 1; i < argc; i++) {
        struct stat sb;
        int n =
            stat(argv[i], &sb) == 0 && S_ISDIR(sb.st_mode) ? run_dir(argv[i]) : run_file(argv[i]);
        if (n <= 0) {
            fprintf(stderr, "replay: %s: %s\n", argv[i], n == 0 ? "no inputs" : "failed");
            return 1;
        }
        printf("replay: %s: %d inputs, no crash\n", argv[i], n);
    }
    return 0;
}
