/* Batched kernel for R-equivalence of segments with the smooth trims of eq. 5.
 * Not batched yet: dfl_rfunc_batch_try_smooth takes no field, so such fields
 * evaluate on the per-point path (rfield.c). */
#include "rfunc/batch_impl.h"

dfl_status dfl_rfunc_batch_try_smooth(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                  dfl_err *err)
{
    (void)d, (void)err;
    *out = NULL;
    return DFL_OK;
}
