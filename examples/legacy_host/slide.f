C     SLIDE - AN EXPLICIT HOST OF EXIC'S CONTACT API WITH COULOMB
C     FRICTION (DOC/API.MD, DOC/FRICTION.MD). THE SKELETON'S SQUARE OF
C     SPRINGS (NODES 1-4, MASS 1, STIFFNESS 1E4) RESTS ON A RIGID
C     FLOOR (NODES 5-8) UNDER GRAVITY G = 10 AND IS LAUNCHED AT VX = 1
C     WITH MU = 0.5 (EXIC_CONTACT_SET_FRICTION): IT SLIDES WITH THE
C     FRICTION FORCE MU N, STOPS AFTER ABOUT V0**2/(2 MU G) = 0.1 AND
C     IS HELD BY STATIC FRICTION. PRINTS THE DISTANCE ITS CENTRE SLID,
C     THE LARGEST |F - MU N| / (MU N) WHILE BOTH CORNERS SLIP, THE
C     MOTION OF THE TWO BOTTOM CORNERS OVER THE LAST 300 STEPS (THE
C     SQUARE STILL RINGS ON ITS SPRINGS ABOVE THEM) AND THE CONSTRAINTS
C     THAT STICK AT THE END (EXIC_CONTACT_PAIR_FRICTION).
      PROGRAM SLIDE
      IMPLICIT NONE
      INTEGER NN, NE, NSTEP
      PARAMETER (NN = 8, NE = 2, NSTEP = 1000)
      DOUBLE PRECISION X0(2,NN), X(2,NN), V(2,NN), A(2,NN), AOLD(2,NN)
      DOUBLE PRECISION VT(2,NN), F(2,NN), FCON(2,NN), AM(NN), PPAIR(1)
      DOUBLE PRECISION DT, T, XC, XC0, XHOLD(2), CREEP, RES(6), FR(4)
      DOUBLE PRECISION RELMAX, AMU
      INTEGER IX(4,NE), IBODY(NE), IPAIR(6,1), IFIX(2,NN)
      INTEGER IH, IERR, NACT, I, K, ISTEP, LMSG
      CHARACTER*200 MSG
      DATA X0 / 0.0D0, 0.0D0, 1.0D0, 0.0D0, 1.0D0, 1.0D0, 0.0D0, 1.0D0,
     &         -1.0D0,-0.5D0, 5.0D0,-0.5D0, 5.0D0, 0.0D0,-1.0D0, 0.0D0 /
      DATA IX / 1, 2, 3, 4,  5, 6, 7, 8 /, IBODY / 1, 2 /
C     PAIR: SLAVE BODY 1, MASTER BODY 2, LAGRANGE, SWEPT, ONE PASS,
C     RIGID MASTER
      DATA IPAIR / 1, 2, 1, 1, 1, 1 /, PPAIR / 0.0D0 /
C
      DT = 5.0D-4
      AMU = 0.5D0
      DO 10 I = 1, NN
         X(1,I) = X0(1,I)
         X(2,I) = X0(2,I)
         AM(I) = 0.25D0
         V(1,I) = 0.0D0
         V(2,I) = 0.0D0
         IFIX(1,I) = 0
         IFIX(2,I) = 0
         IF (I .LE. 4) V(1,I) = 1.0D0
         IF (I .GT. 4) IFIX(1,I) = 1
         IF (I .GT. 4) IFIX(2,I) = 1
   10 CONTINUE
      CALL EXIC_CONTACT_CREATE_MESH(NN, X0, AM, NE, IX, IBODY, 1, IPAIR,
     &                              PPAIR, IH, IERR)
      IF (IERR .NE. 0) GOTO 900
      CALL EXIC_CONTACT_SET_FIXED(IH, NN, IFIX, IERR)
      IF (IERR .NE. 0) GOTO 900
C     STATIC AND DYNAMIC COEFFICIENT 0.5, NO DECAY
      CALL EXIC_CONTACT_SET_FRICTION(IH, 1, AMU, AMU, 0.0D0, IERR)
      IF (IERR .NE. 0) GOTO 900
C
      T = 0.0D0
      CALL SPRFRC(NN, X0, X, AM, IFIX, F, A)
      CALL EXIC_CONTACT_STEP(IH, NN, X, V, A, 0.0D0, DT, FCON, NACT,
     &                       IERR)
      IF (IERR .NE. 0) GOTO 900
      XC0 = 0.5D0
      XHOLD(1) = 0.0D0
      XHOLD(2) = 0.0D0
      CREEP = 0.0D0
      RELMAX = 0.0D0
C
      DO 100 ISTEP = 1, NSTEP
         DO 20 I = 1, NN
            DO 19 K = 1, 2
               X(K,I) = X(K,I) + DT*V(K,I) + 0.5D0*DT*DT*A(K,I)
               AOLD(K,I) = A(K,I)
   19       CONTINUE
   20    CONTINUE
         T = T + DT
         CALL SPRFRC(NN, X0, X, AM, IFIX, F, A)
         DO 30 I = 1, NN
            DO 29 K = 1, 2
               VT(K,I) = V(K,I) + 0.5D0*DT*(AOLD(K,I) + A(K,I))
   29       CONTINUE
   30    CONTINUE
         CALL EXIC_CONTACT_STEP(IH, NN, X, VT, A, DT, DT, FCON, NACT,
     &                          IERR)
         IF (IERR .NE. 0) GOTO 900
         DO 40 I = 1, NN
            DO 39 K = 1, 2
               V(K,I) = V(K,I) + 0.5D0*DT*(AOLD(K,I) + A(K,I))
   39       CONTINUE
   40    CONTINUE
C        RES(1) NORMAL FORCE; FR(1) FRICTION FORCE, FR(2) STICKING,
C        FR(3) SLIPPING CONSTRAINTS OF THE STEP
         CALL EXIC_CONTACT_PAIR_RESULTS(IH, 1, RES, IERR)
         IF (IERR .NE. 0) GOTO 900
         CALL EXIC_CONTACT_PAIR_FRICTION(IH, 1, FR, IERR)
         IF (IERR .NE. 0) GOTO 900
         IF (ISTEP .EQ. 100) WRITE (6, 1000) FR(1), FR(3), RES(1)
         IF (FR(3) .EQ. 2.0D0) RELMAX = MAX(RELMAX,
     &      ABS(FR(1) - AMU*RES(1))/(AMU*RES(1)))
         XC = 0.25D0*(X(1,1) + X(1,2) + X(1,3) + X(1,4))
         IF (ISTEP .EQ. NSTEP - 300) THEN
            XHOLD(1) = X(1,1)
            XHOLD(2) = X(1,2)
         END IF
         IF (ISTEP .GT. NSTEP - 300) CREEP = MAX(CREEP,
     &      ABS(X(1,1) - XHOLD(1)), ABS(X(1,2) - XHOLD(2)))
  100 CONTINUE
      WRITE (6, 1010) XC - XC0, RELMAX, CREEP, NINT(FR(2))
      CALL EXIC_CONTACT_FREE(IH, IERR)
      IF (IERR .NE. 0) GOTO 900
      STOP
C
  900 CALL EXIC_CONTACT_ERROR_MESSAGE(IH, MSG, LMSG, IERR)
      WRITE (6, '(A,A)') ' SLIDE: ', MSG(1:LMSG)
      STOP 1
 1000 FORMAT (' SLIDE: STEP 100 FRICTION', 1PE12.4, ' SLIPPING', 0PF4.0,
     &        ' NORMAL', 1PE12.4)
 1010 FORMAT (' SLIDE: DISTANCE', 1PE23.15, '  FRICTION', 1PE10.2,
     &        '  CREEP', 1PE10.2, '  STICKING', I3)
      END
C
C     SPRING FORCES F OF THE SQUARE (STIFFNESS 1E4, REST LENGTHS FROM
C     X0), GRAVITY -10 M, A = F / M; THE FLOOR'S DOFS ARE FIXED.
      SUBROUTINE SPRFRC(NN, X0, X, AM, IFIX, F, A)
      IMPLICIT NONE
      INTEGER NN, IFIX(2,NN)
      DOUBLE PRECISION X0(2,NN), X(2,NN), AM(NN), F(2,NN), A(2,NN)
      INTEGER IS(2,6), J, K, I1, I2
      DOUBLE PRECISION D(2), D0(2), RL, RL0, S
      DATA IS / 1,2, 2,3, 3,4, 4,1, 1,3, 2,4 /
      DO 10 J = 1, NN
         F(1,J) = 0.0D0
         F(2,J) = -10.0D0*AM(J)
   10 CONTINUE
      DO 30 J = 1, 6
         I1 = IS(1,J)
         I2 = IS(2,J)
         DO 20 K = 1, 2
            D(K) = X(K,I2) - X(K,I1)
            D0(K) = X0(K,I2) - X0(K,I1)
   20    CONTINUE
         RL = SQRT(D(1)**2 + D(2)**2)
         RL0 = SQRT(D0(1)**2 + D0(2)**2)
         S = 1.0D4*(RL - RL0)/RL
         DO 25 K = 1, 2
            F(K,I1) = F(K,I1) + S*D(K)
            F(K,I2) = F(K,I2) - S*D(K)
   25    CONTINUE
   30 CONTINUE
      DO 40 J = 1, NN
         DO 39 K = 1, 2
            A(K,J) = F(K,J)/AM(J)
            IF (IFIX(K,J) .NE. 0) A(K,J) = 0.0D0
   39    CONTINUE
   40 CONTINUE
      RETURN
      END
