/*
 * chost - a C host that calls exic's contact corrector for one step (doc/api.md).
 *
 * A rigid ground segment from node 1 (1, 0) to node 2 (-1, 0) (body below, on the left of
 * 1 -> 2) and a free node 3 at (0, h) falling at speed w; the step from t = 0 with dt would
 * carry it to y = h - w dt < 0. The corrector must close the gap at t(n+2): the corrected
 * position h + dt w_y + dt^2/2 a_y is 0, and the contact force on node 3 is m a_y.
 * The same node then falls again on a fresh handle with mu = 0.5 (exic_c_contact_set_friction)
 * while moving at 3 along the ground: it slides, the friction force is mu times the normal
 * force and opposes the motion (exic_c_contact_pair_friction), and mud > mus is refused.
 * Prints its lines and exits 0 when all holds.
 */
#include <math.h>
#include <stdio.h>
#include "exic_contact.h"

int main(void) {
    const double h = 0.01, w = 2.0, dt = 0.01, m = 1.5;
    double x0[6] = {1.0, 0.0, -1.0, 0.0, 0.0, h};
    double mass[3] = {4.0, 4.0, m};
    int iseg[3] = {1, 2, 1};          /* node 1, node 2, surface 1 */
    int isn[2] = {3, 2};              /* node 3 in slave node set 2 */
    int ipair[6] = {2, 1, EXIC_METHOD_LAGRANGE, EXIC_DETECT_SWEPT, EXIC_ONE_PASS, 1};
    double ppair[1] = {0.0};
    double v[6] = {0.0, 0.0, 0.0, 0.0, 0.0, -w};
    double a[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double fcon[6];
    double res[6];
    char msg[256];
    int ih, ierr, nactive, lmsg, ncon;
    double y2, fy;

    exic_c_contact_create_segments(3, x0, mass, 1, iseg, 1, isn, 1, ipair, ppair, &ih, &ierr);
    if (ierr != EXIC_OK) {
        exic_c_contact_error_message(0, msg, (int)sizeof msg, &lmsg, &ierr);
        fprintf(stderr, "chost: create failed: %s\n", msg);
        return 1;
    }
    exic_c_contact_step(ih, 3, x0, v, a, 0.0, dt, fcon, &nactive, &ierr);
    if (ierr != EXIC_OK) {
        exic_c_contact_error_message(ih, msg, (int)sizeof msg, &lmsg, &ierr);
        fprintf(stderr, "chost: step failed: %s\n", msg);
        return 1;
    }
    exic_c_contact_ncon(ih, &ncon, &ierr);
    exic_c_contact_pair_results(ih, 1, res, &ierr);
    y2 = h + dt * v[5] + 0.5 * dt * dt * a[5];
    fy = fcon[5];
    printf("chost: nactive %d ncon %d y(n+2) %.3e contact force %.6e m*a %.6e pair force %.6e\n",
           nactive, ncon, y2, fy, m * a[5], res[0]);
    /* a bad call: an unknown handle must give an error and a message, not a crash */
    {
        double a2[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, f2[6];
        int n2, e2;
        exic_c_contact_step(ih + 1000, 3, x0, v, a2, 0.0, dt, f2, &n2, &e2);
        if (e2 != EXIC_EHANDLE) return 3;
    }
    exic_c_contact_error_message(ih + 1000, msg, (int)sizeof msg, &lmsg, &ierr);
    printf("chost: unknown handle -> \"%s\"\n", msg);
    exic_c_contact_free(ih, &ierr);
    if (ierr != EXIC_OK) fprintf(stderr, "chost: free failed\n");
    if (nactive != 1 || fabs(y2) > 1e-14 || fabs(fy - m * a[5]) > 1e-12 * fabs(fy) ||
        fabs(res[0] - fy) > 1e-12 * fabs(fy) || lmsg == 0 || ierr != EXIC_OK)
        return 2;
    /* Coulomb friction through the C names */
    {
        double vf[6] = {0.0, 0.0, 0.0, 0.0, 3.0, -w}, af[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        double ff[6], rp[6], rf[4];
        int ihf, nf, ebad;
        exic_c_contact_create_segments(3, x0, mass, 1, iseg, 1, isn, 1, ipair, ppair, &ihf, &ierr);
        if (ierr != EXIC_OK) return 4;
        exic_c_contact_set_friction(ihf, 1, 0.3, 0.5, 0.0, &ebad);
        exic_c_contact_set_friction(ihf, 1, 0.5, 0.5, 0.0, &ierr);
        if (ierr != EXIC_OK || ebad != EXIC_EARGUMENT) return 4;
        exic_c_contact_step(ihf, 3, x0, vf, af, 0.0, dt, ff, &nf, &ierr);
        if (ierr != EXIC_OK) return 4;
        exic_c_contact_pair_results(ihf, 1, rp, &ierr);
        exic_c_contact_pair_friction(ihf, 1, rf, &ierr);
        printf("chost: friction force %.6e normal force %.6e sticking %g slipping %g fx %.6e\n",
               rf[0], rp[0], rf[1], rf[2], ff[4]);
        exic_c_contact_free(ihf, &ierr);
        if (nf != 1 || rf[2] != 1.0 || rf[1] != 0.0 || fabs(rf[0] - 0.5 * rp[0]) > 1e-12 * rp[0] ||
            !(ff[4] < 0.0) || fabs(fabs(ff[4]) - 0.5 * ff[5]) > 1e-12 * ff[5])
            return 5;
    }
    return 0;
}
