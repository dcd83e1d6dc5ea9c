C=======================================================================
C     LHOST - A SMALL EXPLICIT CODE OF THE OLD KIND THAT GETS ITS
C     CONTACT FROM EXIC THROUGH THE LEGACY API (DOC/API.MD).
C
C     PLANE-STRAIN 4-NODE QUADRILATERALS, 2X2 GAUSS, ROW-SUM LUMPED
C     MASS, CENTRAL DIFFERENCES. MATERIAL KINDS:
C       0  RIGID (NO ELEMENT FORCES, NODES DO NOT MOVE)
C       1  NEO-HOOKEAN, TOTAL LAGRANGIAN (THE FORMULATION EXIC USES)
C       2  SMALL-STRAIN LINEAR ELASTIC (A SIMPLER ELEMENT)
C     INPUT ON UNIT 5 (LIST DIRECTED):
C       TITLE
C       NNODE NELEM NMAT NPAIR
C       X Y VX VY IFX IFY                      (NNODE LINES)
C       N1 N2 N3 N4 IBODY IMAT                 (NELEM LINES)
C       IKIND E NU RHO                         (NMAT LINES)
C       ISLAVE IMASTER METHOD DETECT NPASS IRIGID PENALTY (NPAIR LINES)
C       DT TMAX ITIP IVFORM
C       NF, THEN NF NODE NUMBERS          (ONLY WHEN A PAIR HAS METHOD 3)
C     DT > 0 IS A FIXED STEP; DT < 0 ASKS FOR -DT TIMES THE HOST'S OWN
C     STABLE STEP, RECOMPUTED EVERY STEP. IVFORM 1: FULL-STEP VELOCITIES
C     V(N) (EXIC'S SCHEME); 2: HALF-STEP VELOCITIES V(N+1/2) (DYNA'S).
C     METHOD 3 (LAGRANGE WITH MASSLESS CONTACT FACES, EXIC'S
C     LAGRANGE,ENERGY): THE NF NODES GIVEN ARE THE CANDIDATE FACE; LHOST
C     DROPS RIGID AND FIXED NODES, TAKES THE MASSLESS DOFS OF THE RULE OF
C     DECKS (EXIC_CONTACT_FACE_RULE), MOVES THEIR MASS PER DIRECTION TO
C     THE OTHER NODES OF THEIR ELEMENTS, HANDS EXIC THE FACE ROWS OF ITS
C     INITIAL (LINEAR) STIFFNESS (EXIC_CONTACT_SET_FACE_DOFS) AND STEPS
C     WITH EXIC_CONTACT_STEP_FACE (R = -FINT).
C     OUTPUT ON UNIT 6: ONE ROW PER STEP,
C       T  UX VX AX (NODE ITIP)  FN NACT PEN PMAX (PAIR 1)  GMIN
C     GMIN IS THE SMALLEST CORRECTED GAP AT T(N+2) OF THE CONSTRAINTS
C     THAT CARRY FORCE (0 WHEN NONE).
C=======================================================================
      PROGRAM LHOST
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IH, IERR, NACT, ISTEP, IVF, LMSG
      DOUBLE PRECISION T, DT, DTPREV, TMAX, DTIN, DTNEXT
      CHARACTER*200 MSG
C
      CALL RDINP(DTIN, TMAX, IVF)
      CALL REFER
      CALL LMASS
      CALL MKPAIR(IH, IERR)
      IF (IERR .NE. 0) GOTO 900
      CALL EXIC_CONTACT_SET_FIXED(IH, NNODE, IFIX, IERR)
      IF (IERR .NE. 0) GOTO 900
      IF (NFACE .GT. 0) THEN
         CALL FACESU(IH, IERR)
         IF (IERR .NE. 0) GOTO 900
         CALL EXIC_CONTACT_SET_FACE_DOFS(IH, NNODE, AMASD, NFACE, IFACE,
     &                                   IFDF, KRP, KCI, KVAL, IERR)
         IF (IERR .NE. 0) GOTO 900
      END IF
      IF (IVF .EQ. 2) THEN
         CALL EXIC_CONTACT_SET_OPTION(IH, 1, 2, IERR)
         IF (IERR .NE. 0) GOTO 900
      END IF
C
C     T = 0: FORCES, STEP, PREDICTED AND CORRECTED A(0) (DT(N) = 0)
      T = 0.0D0
      ISTEP = 0
      CALL FORCES(IERR)
      IF (IERR .NE. 0) GOTO 910
      CALL CHOOSE(DTIN, DT)
      CALL PREDCT
      DTPREV = 0.0D0
      CALL POSIT
      CALL CSTEP(IH, V, DTPREV, DT, NACT, IERR)
      IF (IERR .NE. 0) GOTO 900
      CALL OUTROW(IH, T)
C
C     THE TIME LOOP
  100 CONTINUE
      IF (T .GE. TMAX*(1.0D0 - 1.0D-12)) GOTO 800
      IF (IVF .EQ. 1) THEN
C        X(N+1) = X(N) + DT(N) V(N) + DT(N)**2/2 A(N)
         CALL MOVE1(DT)
      ELSE
C        V(N+1/2) = V(N-1/2) + (DT(N-1)+DT(N))/2 A(N), X(N+1) = X(N)
C        + DT(N) V(N+1/2); AT N = 0 V(1/2) = V(0) + DT(0)/2 A(0)
         CALL MOVE2(DTPREV, DT)
      END IF
      T = T + DT
      DTPREV = DT
      ISTEP = ISTEP + 1
      CALL FORCES(IERR)
      IF (IERR .NE. 0) GOTO 910
      CALL CHOOSE(DTIN, DTNEXT)
      DT = DTNEXT
      CALL PREDCT
      CALL POSIT
      IF (IVF .EQ. 1) THEN
C        PREDICTOR VELOCITY V~(N+1) = V(N) + DT(N)/2 (A(N) + A~(N+1))
         CALL VTILDE(DTPREV)
         CALL CSTEP(IH, VT, DTPREV, DT, NACT, IERR)
         IF (IERR .NE. 0) GOTO 900
         CALL VUPD(DTPREV)
      ELSE
         CALL CSTEP(IH, V, DTPREV, DT, NACT, IERR)
         IF (IERR .NE. 0) GOTO 900
      END IF
      CALL OUTROW(IH, T)
      GOTO 100
C
  800 CONTINUE
      CALL FINISH(IH, ISTEP)
      CALL EXIC_CONTACT_FREE(IH, IERR)
      STOP
C
  900 CONTINUE
      CALL EXIC_CONTACT_ERROR_MESSAGE(IH, MSG, LMSG, IERR)
      WRITE (6, '(A,A)') '# ERROR: ', MSG(1:MIN(LMSG, 200))
      STOP 1
  910 CONTINUE
      WRITE (6, '(A,I8)') '# ERROR: INVERTED ELEMENT ', IERR
      STOP 1
      END
C
C=======================================================================
      SUBROUTINE RDINP(DT, TMAX, IVF)
C     READ THE INPUT DECK FROM UNIT 5
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION DT, TMAX
      INTEGER IVF, I, K, E
      CHARACTER*80 TITLE
      READ (5, '(A)') TITLE
      READ (5, *) NNODE, NELEM, NMAT, NPAIR
      IF (NNODE .GT. MXNODE .OR. NELEM .GT. MXELEM .OR.
     &    NMAT .GT. MXMAT .OR. NPAIR .GT. MXPAIR) THEN
         WRITE (6, '(A)') '# ERROR: PROBLEM TOO LARGE FOR LHOST'
         STOP 1
      END IF
      DO 10 I = 1, NNODE
         READ (5, *) X0(1,I), X0(2,I), V(1,I), V(2,I),
     &               IFIX(1,I), IFIX(2,I)
   10 CONTINUE
      DO 20 E = 1, NELEM
         READ (5, *) (IX(K,E), K = 1, 4), IBODY(E), IMAT(E)
   20 CONTINUE
      DO 30 K = 1, NMAT
         READ (5, *) KIND(K), YOUNG(K), PNU(K), RHO(K)
C        LAME CONSTANTS FROM E AND NU
         RLAM(K) = YOUNG(K)*PNU(K)/((1.0D0 + PNU(K))*
     &             (1.0D0 - 2.0D0*PNU(K)))
         RMU(K) = YOUNG(K)/(2.0D0*(1.0D0 + PNU(K)))
   30 CONTINUE
      DO 40 K = 1, NPAIR
         READ (5, *) (IPAIR(I,K), I = 1, 6), PPAIR(K)
   40 CONTINUE
      READ (5, *) DT, TMAX, ITIP, IVF
      NFACE = 0
      DO 45 K = 1, NPAIR
         IF (IPAIR(3,K) .EQ. 3) NFACE = -1
   45 CONTINUE
      IF (NFACE .LT. 0) THEN
         READ (5, *) NFACE
         IF (NFACE .GT. MXFACE) THEN
            WRITE (6, '(A)') '# ERROR: TOO MANY FACE NODES FOR LHOST'
            STOP 1
         END IF
         READ (5, *) (IFACE(K), K = 1, NFACE)
      END IF
      DO 50 I = 1, NNODE
         U(1,I) = 0.0D0
         U(2,I) = 0.0D0
         IF (IFIX(1,I) .NE. 0) V(1,I) = 0.0D0
         IF (IFIX(2,I) .NE. 0) V(2,I) = 0.0D0
   50 CONTINUE
      WRITE (6, '(A,A)') '# ', TITLE
      WRITE (6, '(A)') '# T UX VX AX FN NACT PEN PMAX GMIN'
      RETURN
      END
C
C=======================================================================
      SUBROUTINE CSTEP(IH, VV, DTPREV, DT, NACT, IERR)
C     THE CONTACT CALL OF THE STEP: EXIC_CONTACT_STEP, OR WITH MASSLESS
C     FACES EXIC_CONTACT_STEP_FACE WITH R = F_EXT - F_INT = -FINT
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IH, NACT, IERR, I
      DOUBLE PRECISION VV(2,MXNODE), DTPREV, DT
      IF (NFACE .EQ. 0) THEN
         CALL EXIC_CONTACT_STEP(IH, NNODE, X, VV, A, DTPREV, DT, FCON,
     &                          NACT, IERR)
         RETURN
      END IF
      DO 10 I = 1, NNODE
         RFACE(1,I) = -FINT(1,I)
         RFACE(2,I) = -FINT(2,I)
   10 CONTINUE
      CALL EXIC_CONTACT_STEP_FACE(IH, NNODE, X, VV, A, RFACE, DTPREV,
     &                            DT, FCON, NACT, IERR)
      RETURN
      END
C
C=======================================================================
      SUBROUTINE FACESU(IH, IERR)
C     MASSLESS FACES (DOC/IMPACT.MD 3.1-3.2): OF THE CANDIDATES THAT ARE
C     NEITHER RIGID NOR FIXED, THE DOFS THE RULE OF DECKS MAKES MASSLESS
C     (EXIC_CONTACT_FACE_RULE: ALONG THE NORMAL, AGAINST RIGID BODIES ON
C     THE SEGMENTS THAT FACE THEM, NOT IN AN ELEMENT WITH EVERY NODE
C     MASSLESS ALONG THAT DOF); MOVE THEIR LUMPED MASS PER DIRECTION TO
C     THE OTHER NODES OF EACH ELEMENT IN PROPORTION TO THEIR OWN (EQ.
C     I.3); THE FACE ROWS OF THE INITIAL STIFFNESS (THE LINEAR ONE, ALSO
C     THE NEO-HOOKEAN TANGENT AT F = 1) IN CSR, ROW 2(K-1)+D FOR DOF D
C     OF FACE NODE K.
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IH, IERR
      LOGICAL CAND(MXNODE)
      INTEGER I, K, E, N, L, D, R, B, DD, POS(2*MXFACE)
      DOUBLE PRECISION ME(4), MOVED, KEEP, KE(8,8)
      CALL EXIC_CONTACT_FACE_RULE(IH, NNODE, IFDOF, IERR)
      IF (IERR .NE. 0) RETURN
      DO 10 I = 1, NNODE
         CAND(I) = .FALSE.
         IFR(I) = 0
         AMASD(1,I) = AMASS(I)
         AMASD(2,I) = AMASS(I)
   10 CONTINUE
      DO 20 K = 1, NFACE
         I = IFACE(K)
         IF (.NOT. RIGID(I) .AND. IFIX(1,I) .EQ. 0 .AND.
     &       IFIX(2,I) .EQ. 0) CAND(I) = .TRUE.
   20 CONTINUE
      NFACE = 0
      DO 40 I = 1, NNODE
         IF (.NOT. CAND(I)) THEN
            IFDOF(1,I) = 0
            IFDOF(2,I) = 0
         END IF
         IF (IFDOF(1,I) + IFDOF(2,I) .GT. 0) THEN
            NFACE = NFACE + 1
            IFACE(NFACE) = I
            IFDF(1,NFACE) = IFDOF(1,I)
            IFDF(2,NFACE) = IFDOF(2,I)
            IFR(I) = NFACE
         END IF
   40 CONTINUE
C     MASS TRANSFER PER DIRECTION AND ROW LENGTHS (8 ENTRIES PER ELEMENT
C     AND FACE DOF)
      DO 50 R = 1, 2*NFACE
         POS(R) = 0
   50 CONTINUE
      DO 70 E = 1, NELEM
         IF (KIND(IMAT(E)) .EQ. 0) GOTO 70
         N = 0
         DO 55 K = 1, 4
            IF (IFR(IX(K,E)) .GT. 0) N = N + 1
   55    CONTINUE
         IF (N .EQ. 0) GOTO 70
         CALL EMASS(E, ME)
         DO 68 D = 1, 2
            MOVED = 0.0D0
            KEEP = 0.0D0
            DO 60 K = 1, 4
               IF (IFDOF(D,IX(K,E)) .EQ. 1) THEN
                  MOVED = MOVED + ME(K)
               ELSE
                  KEEP = KEEP + ME(K)
               END IF
   60       CONTINUE
            IF (MOVED .EQ. 0.0D0) GOTO 68
            DO 65 K = 1, 4
               I = IX(K,E)
               IF (IFDOF(D,I) .EQ. 1) THEN
                  AMASD(D,I) = AMASD(D,I) - ME(K)
               ELSE
                  AMASD(D,I) = AMASD(D,I) + MOVED*ME(K)/KEEP
               END IF
   65       CONTINUE
   68    CONTINUE
         DO 69 K = 1, 4
            I = IX(K,E)
            IF (IFR(I) .GT. 0) THEN
               POS(2*IFR(I)-1) = POS(2*IFR(I)-1) + 8
               POS(2*IFR(I)) = POS(2*IFR(I)) + 8
            END IF
   69    CONTINUE
   70 CONTINUE
      KRP(1) = 1
      DO 75 R = 1, 2*NFACE
         KRP(R+1) = KRP(R) + POS(R)
         POS(R) = KRP(R)
   75 CONTINUE
      IF (KRP(2*NFACE+1) - 1 .GT. MXNNZ) THEN
         WRITE (6, '(A)') '# ERROR: FACE STIFFNESS TOO LARGE FOR LHOST'
         STOP 1
      END IF
      DO 95 E = 1, NELEM
         IF (KIND(IMAT(E)) .EQ. 0) GOTO 95
         N = 0
         DO 80 K = 1, 4
            IF (IFR(IX(K,E)) .GT. 0) N = N + 1
   80    CONTINUE
         IF (N .EQ. 0) GOTO 95
         CALL ESTIF(E, KE)
         DO 90 K = 1, 4
            IF (IFR(IX(K,E)) .EQ. 0) GOTO 90
            DO 89 D = 1, 2
               R = 2*(IFR(IX(K,E)) - 1) + D
               DO 88 B = 1, 4
                  DO 87 DD = 1, 2
                     L = POS(R)
                     KCI(L) = 2*(IX(B,E) - 1) + DD
                     KVAL(L) = KE(2*(K-1)+D, 2*(B-1)+DD)
                     POS(R) = L + 1
   87             CONTINUE
   88          CONTINUE
   89       CONTINUE
   90    CONTINUE
   95 CONTINUE
C     THE MASSLESS DOFS CARRY NO MASS: NO PREDICTED ACCELERATION
      DO 100 I = 1, NNODE
         DO 99 D = 1, 2
            IF (IFDOF(D,I) .EQ. 1) THEN
               AMASD(D,I) = 0.0D0
               AMINV(D,I) = 0.0D0
            ELSE IF (AMINV(D,I) .GT. 0.0D0) THEN
               AMINV(D,I) = 1.0D0/AMASD(D,I)
            END IF
   99    CONTINUE
  100 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE EMASS(E, ME)
C     ROW-SUM LUMPED MASS OF ELEMENT E (2X2 GAUSS)
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER E, G, K
      DOUBLE PRECISION ME(4), XE(4), YE(4), DNX(4), DNY(4), DJ, GQ
      DOUBLE PRECISION XI, ETA, XIN(4), ETN(4)
      DATA XIN /-1.0D0, 1.0D0, 1.0D0, -1.0D0/
      DATA ETN /-1.0D0, -1.0D0, 1.0D0, 1.0D0/
      GQ = 0.57735026918962576451D0
      DO 10 K = 1, 4
         XE(K) = X0(1,IX(K,E))
         YE(K) = X0(2,IX(K,E))
         ME(K) = 0.0D0
   10 CONTINUE
      DO 20 G = 1, 4
         XI = GQ*XIN(G)
         ETA = GQ*ETN(G)
         CALL GRAD(XE, YE, XI, ETA, DNX, DNY, DJ)
         DO 15 K = 1, 4
            ME(K) = ME(K) + (RHO(IMAT(E))*DJ*0.25D0)
     &            *(1.0D0 + XIN(K)*XI)*(1.0D0 + ETN(K)*ETA)
   15    CONTINUE
   20 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE ESTIF(E, KE)
C     PLANE-STRAIN LINEAR STIFFNESS OF ELEMENT E, 2X2 GAUSS:
C     KE = SUM W B**T D B, D FROM LAMBDA AND MU (DOFS X1 Y1 X2 ...)
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER E, G, IA, IB
      DOUBLE PRECISION KE(8,8), RL, RM, W, GXA, GYA, GXB, GYB
      RL = RLAM(IMAT(E))
      RM = RMU(IMAT(E))
      DO 10 IA = 1, 8
         DO 9 IB = 1, 8
            KE(IA,IB) = 0.0D0
    9    CONTINUE
   10 CONTINUE
      DO 30 G = 1, 4
         W = WDJ(G,E)
         DO 25 IA = 1, 4
            GXA = GDN(IA,G,E)
            GYA = GDN(IA+4,G,E)
            DO 20 IB = 1, 4
               GXB = GDN(IB,G,E)
               GYB = GDN(IB+4,G,E)
               KE(2*IA-1,2*IB-1) = KE(2*IA-1,2*IB-1)
     &            + W*((RL + 2.0D0*RM)*GXA*GXB + RM*GYA*GYB)
               KE(2*IA-1,2*IB) = KE(2*IA-1,2*IB)
     &            + W*(RL*GXA*GYB + RM*GYA*GXB)
               KE(2*IA,2*IB-1) = KE(2*IA,2*IB-1)
     &            + W*(RL*GYA*GXB + RM*GXA*GYB)
               KE(2*IA,2*IB) = KE(2*IA,2*IB)
     &            + W*((RL + 2.0D0*RM)*GYA*GYB + RM*GXA*GXB)
   20       CONTINUE
   25    CONTINUE
   30 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE MKPAIR(IH, IERR)
C     HAND THE MESH, MASSES AND PAIRS TO EXIC
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IH, IERR
      CALL EXIC_CONTACT_CREATE_MESH(NNODE, X0, AMASS, NELEM, IX, IBODY,
     &                              NPAIR, IPAIR, PPAIR, IH, IERR)
      RETURN
      END
C
C=======================================================================
      SUBROUTINE GRAD(XE, YE, XI, ETA, DNX, DNY, DJ)
C     DN/DX, DN/DY AND DET J AT (XI, ETA) OF THE ELEMENT (XE, YE)
      IMPLICIT NONE
      DOUBLE PRECISION XE(4), YE(4), XI, ETA, DNX(4), DNY(4), DJ
      DOUBLE PRECISION XIN(4), ETN(4), DXI(4), DETA(4)
      DOUBLE PRECISION J11, J12, J21, J22, R
      INTEGER K
      DATA XIN /-1.0D0, 1.0D0, 1.0D0, -1.0D0/
      DATA ETN /-1.0D0, -1.0D0, 1.0D0, 1.0D0/
      DO 10 K = 1, 4
         DXI(K) = 0.25D0*XIN(K)*(1.0D0 + ETN(K)*ETA)
         DETA(K) = 0.25D0*ETN(K)*(1.0D0 + XIN(K)*XI)
   10 CONTINUE
      J11 = DXI(1)*XE(1) + DXI(2)*XE(2) + DXI(3)*XE(3) + DXI(4)*XE(4)
      J12 = DXI(1)*YE(1) + DXI(2)*YE(2) + DXI(3)*YE(3) + DXI(4)*YE(4)
      J21 = DETA(1)*XE(1) + DETA(2)*XE(2) + DETA(3)*XE(3)
     &    + DETA(4)*XE(4)
      J22 = DETA(1)*YE(1) + DETA(2)*YE(2) + DETA(3)*YE(3)
     &    + DETA(4)*YE(4)
      DJ = J11*J22 - J12*J21
      R = 1.0D0
      IF (DJ .NE. 0.0D0) R = DJ
      R = 1.0D0/R
      DO 20 K = 1, 4
         DNX(K) = (J22*DXI(K) - J12*DETA(K))*R
         DNY(K) = (J11*DETA(K) - J21*DXI(K))*R
   20 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE REFER
C     REFERENCE GRADIENTS AND WEIGHTS AT THE 2X2 GAUSS POINTS
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION XE(4), YE(4), DNX(4), DNY(4), DJ, GQ
      DOUBLE PRECISION XIN(4), ETN(4)
      INTEGER E, G, K
      DATA XIN /-1.0D0, 1.0D0, 1.0D0, -1.0D0/
      DATA ETN /-1.0D0, -1.0D0, 1.0D0, 1.0D0/
      GQ = 0.57735026918962576451D0
      DO 30 E = 1, NELEM
         DO 10 K = 1, 4
            XE(K) = X0(1,IX(K,E))
            YE(K) = X0(2,IX(K,E))
   10    CONTINUE
         DO 20 G = 1, 4
            CALL GRAD(XE, YE, GQ*XIN(G), GQ*ETN(G), DNX, DNY, DJ)
            IF (DJ .LE. 0.0D0) DJ = 1.0D0
            DO 15 K = 1, 4
               GDN(K,G,E) = DNX(K)
               GDN(K+4,G,E) = DNY(K)
   15       CONTINUE
            WDJ(G,E) = DJ
   20    CONTINUE
   30 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE LMASS
C     ROW-SUM LUMPED MASS (2X2 GAUSS, EMASS) AND INVERSE MASS PER DOF
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION ME(4)
      INTEGER E, K, I
      DO 5 I = 1, NNODE
         AMASS(I) = 0.0D0
         RIGID(I) = .FALSE.
    5 CONTINUE
      DO 30 E = 1, NELEM
         DO 10 K = 1, 4
            IF (KIND(IMAT(E)) .EQ. 0) RIGID(IX(K,E)) = .TRUE.
   10    CONTINUE
         CALL EMASS(E, ME)
         DO 25 K = 1, 4
            AMASS(IX(K,E)) = AMASS(IX(K,E)) + ME(K)
   25    CONTINUE
   30 CONTINUE
      DO 40 I = 1, NNODE
         DO 35 K = 1, 2
            AMINV(K,I) = 0.0D0
            IF (.NOT. RIGID(I) .AND. AMASS(I) .GT. 0.0D0)
     &         AMINV(K,I) = 1.0D0/AMASS(I)
            IF (IFIX(K,I) .NE. 0) AMINV(K,I) = 0.0D0
   35    CONTINUE
   40 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE FORCES(IBAD)
C     INTERNAL FORCES AT THE CURRENT DISPLACEMENTS; IBAD: FIRST ELEMENT
C     WITH J <= 0 (0 IF NONE)
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IBAD, I, E
      IBAD = 0
      DO 10 I = 1, NNODE
         FINT(1,I) = 0.0D0
         FINT(2,I) = 0.0D0
   10 CONTINUE
      DO 20 E = 1, NELEM
         IF (KIND(IMAT(E)) .EQ. 1) CALL FNEOH(E, IBAD)
         IF (KIND(IMAT(E)) .EQ. 2) CALL FLIN(E)
   20 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE FNEOH(E, IBAD)
C     NEO-HOOKEAN ELEMENT, TOTAL LAGRANGIAN, 2X2 GAUSS:
C     P = MU F + (LAMBDA LN J - MU)/J COF(F), F_A += W P GRAD0 N_A
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER E, IBAD, G, K
      DOUBLE PRECISION UX(4), UY(4), FX(4), FY(4), GX(4), GY(4)
      DOUBLE PRECISION F11, F12, F21, F22, JG, JS, LNJ, C, WG
      DOUBLE PRECISION P11, P12, P21, P22, RL, RM
      RL = RLAM(IMAT(E))
      RM = RMU(IMAT(E))
      DO 10 K = 1, 4
         UX(K) = U(1,IX(K,E))
         UY(K) = U(2,IX(K,E))
         FX(K) = 0.0D0
         FY(K) = 0.0D0
   10 CONTINUE
      DO 30 G = 1, 4
         DO 15 K = 1, 4
            GX(K) = GDN(K,G,E)
            GY(K) = GDN(K+4,G,E)
   15    CONTINUE
         F11 = 1.0D0 + (UX(1)*GX(1) + UX(2)*GX(2) + UX(3)*GX(3)
     &       + UX(4)*GX(4))
         F12 = UX(1)*GY(1) + UX(2)*GY(2) + UX(3)*GY(3) + UX(4)*GY(4)
         F21 = UY(1)*GX(1) + UY(2)*GX(2) + UY(3)*GX(3) + UY(4)*GX(4)
         F22 = 1.0D0 + (UY(1)*GY(1) + UY(2)*GY(2) + UY(3)*GY(3)
     &       + UY(4)*GY(4))
         JG = F11*F22 - F12*F21
         IF (JG .LE. 0.0D0 .AND. IBAD .EQ. 0) IBAD = E
         JS = 1.0D0
         IF (JG .GT. 0.0D0) JS = JG
         LNJ = LOG(JS)
         C = (RL*LNJ - RM)/JS
         WG = WDJ(G,E)
         P11 = WG*(RM*F11 + C*F22)
         P12 = WG*(RM*F12 - C*F21)
         P21 = WG*(RM*F21 - C*F12)
         P22 = WG*(RM*F22 + C*F11)
         DO 20 K = 1, 4
            FX(K) = FX(K) + P11*GX(K) + P12*GY(K)
            FY(K) = FY(K) + P21*GX(K) + P22*GY(K)
   20    CONTINUE
   30 CONTINUE
      DO 40 K = 1, 4
         FINT(1,IX(K,E)) = FINT(1,IX(K,E)) + FX(K)
         FINT(2,IX(K,E)) = FINT(2,IX(K,E)) + FY(K)
   40 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE FLIN(E)
C     SMALL-STRAIN LINEAR ELASTIC ELEMENT (PLANE STRAIN), 2X2 GAUSS
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER E, G, K
      DOUBLE PRECISION UX(4), UY(4), GX(4), GY(4)
      DOUBLE PRECISION E11, E22, G12, S11, S22, S12, WG, RL, RM
      RL = RLAM(IMAT(E))
      RM = RMU(IMAT(E))
      DO 10 K = 1, 4
         UX(K) = U(1,IX(K,E))
         UY(K) = U(2,IX(K,E))
   10 CONTINUE
      DO 30 G = 1, 4
         E11 = 0.0D0
         E22 = 0.0D0
         G12 = 0.0D0
         DO 15 K = 1, 4
            GX(K) = GDN(K,G,E)
            GY(K) = GDN(K+4,G,E)
            E11 = E11 + UX(K)*GX(K)
            E22 = E22 + UY(K)*GY(K)
            G12 = G12 + UX(K)*GY(K) + UY(K)*GX(K)
   15    CONTINUE
         WG = WDJ(G,E)
         S11 = WG*((RL + 2.0D0*RM)*E11 + RL*E22)
         S22 = WG*(RL*E11 + (RL + 2.0D0*RM)*E22)
         S12 = WG*RM*G12
         DO 20 K = 1, 4
            FINT(1,IX(K,E)) = FINT(1,IX(K,E)) + S11*GX(K) + S12*GY(K)
            FINT(2,IX(K,E)) = FINT(2,IX(K,E)) + S12*GX(K) + S22*GY(K)
   20    CONTINUE
   30 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE CHOOSE(DTIN, DT)
C     THE STEP: FIXED (DTIN > 0) OR -DTIN X THE SMALLEST L/C OF THE
C     DEFORMABLE ELEMENTS AT THE CURRENT GEOMETRY (L = AREA/DIAGONAL)
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION DTIN, DT, D1X, D1Y, D2X, D2Y, AREA, DMAX, CC
      DOUBLE PRECISION XE(4), YE(4), DTE
      INTEGER E, K, M
      IF (DTIN .GT. 0.0D0) THEN
         DT = DTIN
         RETURN
      END IF
      DT = 1.0D30
      DO 20 E = 1, NELEM
         M = IMAT(E)
         IF (KIND(M) .EQ. 0) GOTO 20
         DO 10 K = 1, 4
            XE(K) = X0(1,IX(K,E)) + U(1,IX(K,E))
            YE(K) = X0(2,IX(K,E)) + U(2,IX(K,E))
   10    CONTINUE
         D1X = XE(3) - XE(1)
         D1Y = YE(3) - YE(1)
         D2X = XE(4) - XE(2)
         D2Y = YE(4) - YE(2)
         AREA = 0.5D0*(D1X*D2Y - D1Y*D2X)
         DMAX = SQRT(MAX(D1X**2 + D1Y**2, D2X**2 + D2Y**2))
         CC = SQRT((RLAM(M) + 2.0D0*RMU(M))/RHO(M))
         DTE = AREA/DMAX/CC
         IF (DTE .LT. DT) DT = DTE
   20 CONTINUE
      DT = -DTIN*DT
      RETURN
      END
C
C=======================================================================
      SUBROUTINE PREDCT
C     PREDICTED ACCELERATIONS A~ = M**-1 (F - P), NO EXTERNAL FORCES
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER I
      DO 10 I = 1, NNODE
         AOLD(1,I) = A(1,I)
         AOLD(2,I) = A(2,I)
         A(1,I) = AMINV(1,I)*(0.0D0 - FINT(1,I))
         A(2,I) = AMINV(2,I)*(0.0D0 - FINT(2,I))
   10 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE POSIT
C     CURRENT POSITIONS X = X0 + U
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER I
      DO 10 I = 1, NNODE
         X(1,I) = X0(1,I) + U(1,I)
         X(2,I) = X0(2,I) + U(2,I)
   10 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE MOVE1(DT)
C     X(N+1) = X(N) + DT V(N) + DT**2/2 A(N)
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION DT
      INTEGER I, K
      DO 10 I = 1, NNODE
         DO 5 K = 1, 2
            U(K,I) = U(K,I) + (DT*V(K,I) + (0.5D0*DT*DT)*A(K,I))
    5    CONTINUE
   10 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE MOVE2(DTPREV, DT)
C     HALF-STEP FORM: V(N+1/2) = V(N-1/2) + (DT(N-1) + DT(N))/2 A(N),
C     X(N+1) = X(N) + DT(N) V(N+1/2) (AT N = 0, DT(N-1) = 0)
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION DTPREV, DT, DTAV
      INTEGER I, K
      DTAV = 0.5D0*(DTPREV + DT)
      DO 10 I = 1, NNODE
         DO 5 K = 1, 2
            V(K,I) = V(K,I) + DTAV*A(K,I)
            U(K,I) = U(K,I) + DT*V(K,I)
    5    CONTINUE
   10 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE VTILDE(DTPREV)
C     V~(N+1) = V(N) + DT(N)/2 (A(N) + A~(N+1))
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION DTPREV
      INTEGER I, K
      DO 10 I = 1, NNODE
         DO 5 K = 1, 2
            VT(K,I) = V(K,I) + (0.5D0*DTPREV)*(AOLD(K,I) + A(K,I))
    5    CONTINUE
   10 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE VUPD(DTPREV)
C     V(N+1) = V(N) + DT(N)/2 (A(N) + A(N+1))
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION DTPREV
      INTEGER I, K
      DO 10 I = 1, NNODE
         DO 5 K = 1, 2
            V(K,I) = V(K,I) + (0.5D0*DTPREV)*(AOLD(K,I) + A(K,I))
    5    CONTINUE
   10 CONTINUE
      RETURN
      END
C
C=======================================================================
      SUBROUTINE OUTROW(IH, T)
C     ONE HISTORY ROW: TIP, PAIR 1 RESULTS, SMALLEST CORRECTED GAP
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IH, IERR, NCON, I
      DOUBLE PRECISION T, RES(6), GMIN
      CALL EXIC_CONTACT_PAIR_RESULTS(IH, 1, RES, IERR)
      CALL EXIC_CONTACT_CONSTRAINTS(IH, MXCON, NCON, ICON, RCON, IERR)
      GMIN = 0.0D0
      IF (IERR .EQ. 0) THEN
         DO 10 I = 1, NCON
            IF (RCON(1,I) .GT. 0.0D0) GMIN = MIN(GMIN, RCON(6,I))
   10    CONTINUE
      END IF
      WRITE (6, '(1P,9E24.16)') T, U(1,ITIP), V(1,ITIP), A(1,ITIP),
     &   RES(1), RES(4), RES(5), RES(6), GMIN
      RETURN
      END
C
C=======================================================================
      SUBROUTINE FINISH(IH, ISTEP)
C     CLOSING LINES: STEPS, CONTACT WORK, LARGEST PENETRATION
      IMPLICIT NONE
      INCLUDE 'host.inc'
      INTEGER IH, ISTEP, IERR
      DOUBLE PRECISION WCON, PENMAX, EKIN, ESTR
      CALL EXIC_CONTACT_WORK(IH, WCON, PENMAX, IERR)
      CALL ENERGY(EKIN, ESTR)
      WRITE (6, '(A,I8)') '# STEPS ', ISTEP
      WRITE (6, '(A,1P,2E24.16)') '# KINETIC AND STRAIN ENERGY ', EKIN,
     &   ESTR
      WRITE (6, '(A,1P,E24.16)') '# CONTACT WORK ', WCON
      WRITE (6, '(A,1P,E24.16)') '# LARGEST PENETRATION ', PENMAX
      RETURN
      END
C
C=======================================================================
      SUBROUTINE ENERGY(EKIN, ESTR)
C     KINETIC ENERGY 1/2 M V**2 AND STRAIN ENERGY: NEO-HOOKEAN
C     W = LAMBDA/2 (LN J)**2 + MU/2 (I1 - 3) - MU LN J (I1 = TR C + 1),
C     LINEAR W = 1/2 EPS : D : EPS, AT THE 2X2 GAUSS POINTS
      IMPLICIT NONE
      INCLUDE 'host.inc'
      DOUBLE PRECISION EKIN, ESTR, F11, F12, F21, F22, JG, LNJ, RL, RM
      DOUBLE PRECISION GX, GY
      INTEGER I, E, G, K
      EKIN = 0.0D0
      DO 10 I = 1, NNODE
         IF (NFACE .GT. 0) THEN
            EKIN = EKIN + 0.5D0*(AMASD(1,I)*V(1,I)**2 +
     &                           AMASD(2,I)*V(2,I)**2)
         ELSE
            EKIN = EKIN + 0.5D0*AMASS(I)*(V(1,I)**2 + V(2,I)**2)
         END IF
   10 CONTINUE
      ESTR = 0.0D0
      DO 40 E = 1, NELEM
         IF (KIND(IMAT(E)) .EQ. 0) GOTO 40
         RL = RLAM(IMAT(E))
         RM = RMU(IMAT(E))
         DO 30 G = 1, 4
            F11 = 0.0D0
            F12 = 0.0D0
            F21 = 0.0D0
            F22 = 0.0D0
            DO 20 K = 1, 4
               GX = GDN(K,G,E)
               GY = GDN(K+4,G,E)
               F11 = F11 + U(1,IX(K,E))*GX
               F12 = F12 + U(1,IX(K,E))*GY
               F21 = F21 + U(2,IX(K,E))*GX
               F22 = F22 + U(2,IX(K,E))*GY
   20       CONTINUE
            IF (KIND(IMAT(E)) .EQ. 1) THEN
               F11 = F11 + 1.0D0
               F22 = F22 + 1.0D0
               JG = F11*F22 - F12*F21
               LNJ = LOG(MAX(JG, 1.0D-300))
               ESTR = ESTR + WDJ(G,E)*(0.5D0*RL*LNJ**2 + 0.5D0*RM*
     &            (F11**2 + F12**2 + F21**2 + F22**2 - 2.0D0) - RM*LNJ)
            ELSE
               ESTR = ESTR + WDJ(G,E)*(0.5D0*(RL + 2.0D0*RM)*
     &            (F11**2 + F22**2) + RL*F11*F22
     &            + 0.5D0*RM*(F12 + F21)**2)
            END IF
   30    CONTINUE
   40 CONTINUE
      RETURN
      END
