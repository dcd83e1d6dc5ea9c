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
 * Last, method 3 (massless contact faces, doc/impact.md): node 3 is a massless face node tied by
 * springs k to a node 4 one above it (exic_c_contact_set_face); both fall at w, so the free
 * solve carries node 3 to h - w dt < 0 and the face block places it on the ground with the
 * spring force k (w dt - h) (exic_c_contact_step_face).
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
    /* massless contact face through the C names */
    {
        const double k = 100.0;
        double x4[8] = {1.0, 0.0, -1.0, 0.0, 0.0, h, 0.0, h + 1.0};
        double m4[4] = {4.0, 4.0, m, m}, mf[4] = {4.0, 4.0, 0.0, 2.0 * m};
        double v4[8] = {0.0, 0.0, 0.0, 0.0, 0.0, -w, 0.0, -w}, a4[8] = {0}, r4[8] = {0}, f4[8];
        int ipe[6] = {2, 1, EXIC_METHOD_ENERGY, EXIC_DETECT_SWEPT, EXIC_ONE_PASS, 1};
        int iface[1] = {3}, irp[3] = {1, 3, 5}, ici[4] = {5, 7, 6, 8};
        double kval[4] = {k, -k, k, -k};
        int ihe, ne;
        double y3;
        exic_c_contact_create_segments(4, x4, m4, 1, iseg, 1, isn, 1, ipe, ppair, &ihe, &ierr);
        if (ierr != EXIC_OK) return 6;
        exic_c_contact_set_face(ihe, 4, mf, 1, iface, irp, ici, kval, &ierr);
        if (ierr != EXIC_OK) return 6;
        exic_c_contact_step_face(ihe, 4, x4, v4, a4, r4, 0.0, dt, f4, &ne, &ierr);
        if (ierr != EXIC_OK) return 6;
        y3 = h + dt * v4[5] + 0.5 * dt * dt * a4[5];
        printf("chost: massless face: nactive %d y(n+2) %.3e contact force %.6e k (w dt - h) %.6e\n",
               ne, y3, f4[5], k * (w * dt - h));
        exic_c_contact_free(ihe, &ierr);
        if (ne != 1 || fabs(y3) > 1e-14 || fabs(f4[5] - k * (w * dt - h)) > 1e-12 * k) return 7;
    }
    return 0;
}
