/* Batched kernel for R-conjunction (eq. 7) of segment parts.
 * Not batched yet: dfl_rfunc_batch_try_rconj takes no field, so such fields
 * evaluate on the per-point path (rfield.c). */
#include "rfunc/batch_impl.h"

dfl_status dfl_rfunc_batch_try_rconj(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                  dfl_err *err)
{
    (void)d, (void)err;
    *out = NULL;
    return DFL_OK;
}
