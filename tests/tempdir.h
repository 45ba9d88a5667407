/* tests/tempdir.h - a fresh directory for a test's files.  The includer
   defines _POSIX_C_SOURCE 200809L (mkdtemp) before any include. */
#ifndef MANYLODS_TEST_TEMPDIR_H
#define MANYLODS_TEST_TEMPDIR_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Create $TMPDIR/manylods-NAME-<6 random characters> (/tmp without
   TMPDIR) and write its path into out (size bytes).  Returns 1, or 0 with
   errno set. */
static inline int test_temp_dir(char *out, size_t size, const char *name)
{
    const char *tmp = getenv("TMPDIR");
    int n = snprintf(out, size, "%s/manylods-%s-", tmp && *tmp ? tmp : "/tmp", name);
    if (n < 0 || (size_t)n + 7 > size) return 0;
    memset(out + n, 'X', 6); /* the template mkdtemp fills in */
    out[n + 6] = '\0';
    return mkdtemp(out) != NULL;
}

#endif
