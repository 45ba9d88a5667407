/* fuzz/fz_errors.h - the check of a failed library call that the
   harnesses of the C library share (fuzz_pipeline.c, fuzz_megaviews.c).
   Include after manylods.h and fuzz.h. */
#ifndef MANYLODS_FZ_ERRORS_H
#define MANYLODS_FZ_ERRORS_H

static const char *fz_where = ""; /* the call being checked, for messages */

/* A failed call: a real error code, matching error.code, with a message. */
static void check_error(mlod_result res, const mlod_error *e)
{
    size_t len = 0;
    FZ_REQUIRE(res != MLOD_OK && res >= MLOD_ERROR_INVALID_ARGUMENT && res <= MLOD_ERROR_CANCELLED,
               "%s: not an error code: %d", fz_where, (int)res);
    FZ_REQUIRE(e->code == res, "%s: returned %s, error.code %s", fz_where, mlod_result_name(res),
               mlod_result_name(e->code));
    while (len < sizeof e->message && e->message[len]) len++;
    FZ_REQUIRE(len > 0 && len < sizeof e->message, "%s: %s with an empty or unterminated message", fz_where,
               mlod_result_name(res));
}

#endif
