/* What the knobs and columns mean: one line each, with the unit, for
 * `dflab help STUDY` and `dflab help STUDY --columns` (help.c).
 *
 * The keys' types, ranges and defaults come from the getters themselves
 * (io/config.h read record); what a key means is not something a getter
 * can check, so it lives here, in one table per concern (meaning.c), and
 * tests/cli/test_help_meaning.c runs `dflab help` over every config under
 * configs/ and fails on any key that has no meaning: a new getter without
 * a line here fails the suite.
 *
 *   dfl_key_meaning    the meaning of [sec] key as study reads it
 *   dfl_study_columns  prints the column glossary of a study
 *   dfl_study_column   its entries one at a time
 */
#ifndef DFL_EXPERIMENTS_MEANING_H
#define DFL_EXPERIMENTS_MEANING_H

#include <stdbool.h>
#include <stdio.h>

#include "harness/experiment.h"

/* The one-line meaning (with unit) of key in section sec as study reads
 * it; sections a config names freely (a shape, a case) match by key.  The
 * most specific entry wins: (study, sec, key), (study, any, key),
 * (any, sec, key), (any, any, key).  "" when there is none. */
const char *dfl_key_meaning(const char *study, const char *sec, const char *key);

/* Prints the columns of study's tables, each with its meaning, then the
 * columns every table has (point, the swept keys).  False (nothing
 * printed) when the study has no glossary entries. */
bool dfl_study_columns(const dfl_study *study, FILE *out);

/* The glossary entries of the study named study, one at a time (i = 0, 1,
 * ...; false past the last), in the order dfl_study_columns prints them:
 * *col is the column's name (a * stands for several; <...> for a part of
 * the name, e.g. <section>.<key>, slice<k>), *meaning its line, *own false
 * for the entries every table shares (point, the swept keys, vti), which a
 * table need not have.  tests/experiments/harness/test_column_glossary.c
 * runs every study and checks its CSV header against these entries. */
bool dfl_study_column(const char *study, size_t i, const char **col, const char **meaning,
                      bool *own);

#endif
