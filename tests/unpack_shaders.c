/* tests/unpack_shaders.c - the modules that manylods_vk.h unpacks from its
   text (mlodvk__unpack, mlodvk__spirv) are, word for word, the modules
   shaders/embed.sh compiled and packed (SPV_OUT).  tests/check_shaders.sh
   builds it against the header being checked (-I) and runs it with those
   files in the order of the header's module list.

   Usage: unpack_shaders MODULE.spv ...   (every module, in order)
   Exit status 0 when every module matches, 1 otherwise. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_VK_IMPLEMENTATION
#include "manylods_vk.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    mlod_allocator a = mlod_default_allocator();
    mlod_error error;
    uint32_t *all = NULL;
    size_t at = 0;
    int m, failed = 0;
    if (argc - 1 != MLODVK__SPV_MODULES) {
        printf("FAIL: %d files for %d modules\n", argc - 1, (int)MLODVK__SPV_MODULES);
        return 1;
    }
    if (mlodvk__unpack(&a, &all, &error) != MLOD_OK) {
        printf("FAIL: mlodvk__unpack: %s\n", error.message);
        return 1;
    }
    for (m = 0; m < MLODVK__SPV_MODULES; m++) {
        FILE *f = fopen(argv[1 + m], "rb");
        size_t words = mlodvk__spv_words[m], k = 0;
        uint32_t w;
        int same = f != NULL;
        while (same && fread(&w, 4, 1, f) == 1) same = k < words && all[at + k++] == w;
        same = same && k == words;
        if (f) fclose(f);
        if (!same) {
            printf("FAIL: module %d (%s) unpacks to other words than the file\n", m, argv[1 + m]);
            failed++;
        }
        at += words;
    }
    if (at != MLODVK__SPV_WORDS) {
        printf("FAIL: the modules' sizes add up to %lu words, the text states %lu\n", (unsigned long)at,
               (unsigned long)MLODVK__SPV_WORDS);
        failed++;
    }
    mlodvk__free(&a, all);
    if (!failed) printf("%d modules (%lu words) unpack to what the compiler made\n", m, (unsigned long)at);
    return failed != 0;
}
