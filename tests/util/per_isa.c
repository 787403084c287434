/* tests/util/per_isa.h */
#include "util/per_isa.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/isa.h"

int dfl_test_per_isa(int (*check)(const void *ctx), const void *ctx)
{
    int ran = 0;
    for (int isa = 0; isa < DFL_ISA_COUNT; isa++) {
        if (!dfl_isa_cpu_has((dfl_isa)isa)) continue;
        fflush(NULL);
        const pid_t pid = fork();
        cr_assert(pid >= 0);
        if (pid == 0) {
            setenv("DFL_ISA", dfl_isa_name((dfl_isa)isa), 1);
            if (dfl_isa_active() != (dfl_isa)isa) _exit(3);
            const int bad = check(ctx);
            fflush(NULL);
            _exit(bad ? 1 : 0);
        }
        int st = 0;
        cr_assert(waitpid(pid, &st, 0) == pid);
        cr_expect(WIFEXITED(st) && WEXITSTATUS(st) == 0,
                  "DFL_ISA=%s: %s %d (1: a check failed, 3: the ISA was not taken)",
                  dfl_isa_name((dfl_isa)isa), WIFEXITED(st) ? "exit" : "signal",
                  WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
        ran++;
    }
    return ran;
}
