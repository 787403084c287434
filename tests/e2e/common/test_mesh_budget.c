
/* A shape no method applies to is still built for its points and
 * reference: R-functions of 2D curves on Wuson build no field, yet the
 * mesh's bound is charged (key [study] shapes). */
Test(e2e_mesh_budget, compare_charges_a_shape_without_fields, .timeout = 120)
{
    char dir[256], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(args, sizeof args,
             "plan configs/compare/quick.ini --set study.methods=m_rfunc --set "
             "study.shapes=s_wuson --set study.memory_budget=0.1 --out %s/o",
             dir);
    const int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2, "%s", msg);
    cr_expect(strstr(msg, "study.shapes") && strstr(msg, "the shape [s_wuson]"), "%s", msg);
    free(msg);
    e2e_rmtree(dir);
}
