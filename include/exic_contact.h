/*
 * exic_contact.h - C interface of exic's legacy contact API (see doc/api.md).
 *
 * The same calls as the Fortran 77 entry points EXIC_CONTACT_*, under the names
 * exic_c_contact_*. Input scalars by value, outputs through pointers, ierr last
 * (0 success, 1 bad argument, 2 unknown handle, 3 set-up failure, 4 corrector failure;
 * exic_c_contact_error_message gives the reason). Arrays are column-major Fortran arrays:
 * x[2*(i-1)] and x[2*(i-1)+1] are the x and y of node i, ipair[6*(k-1)+j-1] is entry j of
 * pair k. Node, body, surface and pair numbers are 1-based, as in Fortran.
 *
 * Link (the line of doc/api.md, "Install and link"; no HDF5, no Gmsh):
 * cc -O2 -I$PREFIX/include host.c -L$PREFIX/lib -lexic -lldl -lamd -llapack -lblas -lgomp -lgfortran -lm
 */
#ifndef EXIC_CONTACT_H
#define EXIC_CONTACT_H

#ifdef __cplusplus
extern "C" {
#endif

/* error codes */
#define EXIC_OK 0
#define EXIC_EARGUMENT 1
#define EXIC_EHANDLE 2
#define EXIC_ESETUP 3
#define EXIC_ESOLVE 4

/* ipair[6*(k-1) + ...] entries and values */
#define EXIC_METHOD_LAGRANGE 1
#define EXIC_METHOD_PENALTY 2
#define EXIC_METHOD_ENERGY 3  /* Lagrange with massless contact faces (LAGRange,ENERgy) */
#define EXIC_DETECT_SWEPT 1
#define EXIC_DETECT_STATIC 2
#define EXIC_ONE_PASS 1
#define EXIC_TWO_PASS 2

/* options of exic_c_contact_set_option */
#define EXIC_OPT_VELOCITY_FORM 1
#define EXIC_VELOCITY_FULL_STEP 1 /* v~(n+1) = v(n) + dt(n)/2 (a(n) + a~(n+1)) */
#define EXIC_VELOCITY_HALF_STEP 2 /* v(n+1/2) = v(n) + dt(n)/2 a(n)           */

void exic_c_contact_create_mesh(int nnode, const double *x0, const double *amass, int nelem,
                                const int *ix, const int *ibody, int npair, const int *ipair,
                                const double *ppair, int *ih, int *ierr);
void exic_c_contact_create_segments(int nnode, const double *x0, const double *amass, int nseg,
                                    const int *iseg, int nsn, const int *isn, int npair,
                                    const int *ipair, const double *ppair, int *ih, int *ierr);
void exic_c_contact_set_fixed(int ih, int nnode, const int *ifix, int *ierr);
void exic_c_contact_set_pair(int ih, int ipair, const int *iopt, double pen, int *ierr);
void exic_c_contact_set_option(int ih, int iopt, int ival, int *ierr);
void exic_c_contact_step(int ih, int nnode, const double *x, const double *v, double *a,
                         double dtprev, double dt, double *fcon, int *nactive, int *ierr);
/* massless contact faces of method-3 pairs (doc/api.md, doc/impact.md section 3): amass the
 * host's masses after the face transfer, iface[nf] face nodes, irp[2 nf + 1], ici, val the
 * face dofs' rows of the initial stiffness (1-based CSR) */
void exic_c_contact_set_face(int ih, int nnode, const double *amass, int nf, const int *iface,
                             const int *irp, const int *ici, const double *val, int *ierr);
/* the same with massless dofs per direction (doc/impact.md eq. I.3a, I.3b): amass[2 nnode]
 * the masses per dof, ifdof[2 nf] 1 where dof d of iface[k] is massless, else 0 */
void exic_c_contact_set_face_dofs(int ih, int nnode, const double *amass, int nf, const int *iface,
                                  const int *ifdof, const int *irp, const int *ici,
                                  const double *val, int *ierr);
/* ifdof[2 nnode]: 1 on the dofs the rule of decks makes massless (doc/impact.md 3.1) */
void exic_c_contact_face_rule(int ih, int nnode, int *ifdof, int *ierr);
/* the step of a handle with massless faces: r = f_ext - f_int at t(n+1) */
void exic_c_contact_step_face(int ih, int nnode, const double *x, const double *v, double *a,
                              const double *r, double dtprev, double dt, double *fcon,
                              int *nactive, int *ierr);
void exic_c_contact_pair_results(int ih, int ipair, double *res, int *ierr);
/* Coulomb friction of pair ipair: static amus, dynamic amud <= amus, decay with slip speed
 * (0: amus at rest, amud sliding); amus = 0: frictionless (doc/friction.md) */
void exic_c_contact_set_friction(int ih, int ipair, double amus, double amud, double decay, int *ierr);
/* res[4]: friction force, sticking and slipping constraints of the last step, dissipation */
void exic_c_contact_pair_friction(int ih, int ipair, double *res, int *ierr);
void exic_c_contact_ncon(int ih, int *ncon, int *ierr);
void exic_c_contact_constraints(int ih, int mcon, int *ncon, int *icon, double *rcon, int *ierr);
void exic_c_contact_work(int ih, double *wcon, double *penmax, int *ierr);
void exic_c_contact_free(int ih, int *ierr);
void exic_c_contact_error_message(int ih, char *msg, int msglen, int *lmsg, int *ierr);

#ifdef __cplusplus
}
#endif

#endif /* EXIC_CONTACT_H */
