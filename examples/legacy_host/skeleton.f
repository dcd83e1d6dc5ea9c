C     SKELETON - THE SMALLEST COMPLETE EXPLICIT HOST OF EXIC'S CONTACT
C     API (DOC/API.MD SHOWS THIS FILE). A 1 X 1 SQUARE (NODES 1-4,
C     HELD TOGETHER BY SIX SPRINGS: ITS FOUR EDGES AND TWO DIAGONALS)
C     MOVES AT VX = 1 TOWARDS A RIGID BLOCK (NODES 5-8) 0.1 AWAY.
C     CENTRAL DIFFERENCES, LUMPED MASSES, ONE EXIC_CONTACT_STEP PER
C     STEP: THE CORRECTED ACCELERATIONS CLOSE EVERY GAP AT T(N+2).
C     PRINTS ONE ROW PER 20 STEPS AND A LAST LINE WITH THE LARGEST
C     PENETRATION OF A SQUARE NODE INTO THE BLOCK.
      PROGRAM SKELTN
      IMPLICIT NONE
      INTEGER NN, NE, NSTEP
      PARAMETER (NN = 8, NE = 2, NSTEP = 200)
      DOUBLE PRECISION X0(2,NN), X(2,NN), V(2,NN), A(2,NN), AOLD(2,NN)
      DOUBLE PRECISION VT(2,NN), F(2,NN), FCON(2,NN), AM(NN), PPAIR(1)
      DOUBLE PRECISION DT, T, PEN, PENMAX, FX
      INTEGER IX(4,NE), IBODY(NE), IPAIR(6,1), IFIX(2,NN)
      INTEGER IH, IERR, NACT, NACTMX, I, K, ISTEP, LMSG
      CHARACTER*200 MSG
      DATA X0 / 0.0D0, 0.0D0, 1.0D0, 0.0D0, 1.0D0, 1.0D0, 0.0D0, 1.0D0,
     &          1.1D0,-0.5D0, 2.1D0,-0.5D0, 2.1D0, 1.5D0, 1.1D0, 1.5D0 /
      DATA IX / 1, 2, 3, 4,  5, 6, 7, 8 /, IBODY / 1, 2 /
C     PAIR: SLAVE BODY 1, MASTER BODY 2, LAGRANGE, SWEPT, ONE PASS,
C     RIGID MASTER
      DATA IPAIR / 1, 2, 1, 1, 1, 1 /, PPAIR / 0.0D0 /
C
      DT = 5.0D-3
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
C
C     T = 0: A~(0) FROM THE FORCES, CORRECTED WITH V(0) AND DTPREV = 0
      T = 0.0D0
      CALL SPRING(NN, X0, X, AM, IFIX, F, A)
      CALL EXIC_CONTACT_STEP(IH, NN, X, V, A, 0.0D0, DT, FCON, NACT,
     &                       IERR)
      IF (IERR .NE. 0) GOTO 900
      PENMAX = 0.0D0
      NACTMX = 0
C
      DO 100 ISTEP = 1, NSTEP
C        X(N+1) = X(N) + DT V(N) + DT**2/2 A(N)
         DO 20 I = 1, NN
            DO 19 K = 1, 2
               X(K,I) = X(K,I) + DT*V(K,I) + 0.5D0*DT*DT*A(K,I)
               AOLD(K,I) = A(K,I)
   19       CONTINUE
   20    CONTINUE
         T = T + DT
C        PREDICTED A~(N+1) = F / M AND V~(N+1) = V(N) + DT/2 (A(N) + A~)
         CALL SPRING(NN, X0, X, AM, IFIX, F, A)
         DO 30 I = 1, NN
            DO 29 K = 1, 2
               VT(K,I) = V(K,I) + 0.5D0*DT*(AOLD(K,I) + A(K,I))
   29       CONTINUE
   30    CONTINUE
C        THE CONTACT CORRECTOR: A~(N+1) IN, A(N+1) OUT
         CALL EXIC_CONTACT_STEP(IH, NN, X, VT, A, DT, DT, FCON, NACT,
     &                          IERR)
         IF (IERR .NE. 0) GOTO 900
C        V(N+1) = V(N) + DT/2 (A(N) + A(N+1))
         DO 40 I = 1, NN
            DO 39 K = 1, 2
               V(K,I) = V(K,I) + 0.5D0*DT*(AOLD(K,I) + A(K,I))
   39       CONTINUE
   40    CONTINUE
         FX = 0.0D0
         DO 50 I = 1, 4
            PEN = X(1,I) - 1.1D0
            IF (PEN .GT. PENMAX) PENMAX = PEN
            FX = FX + FCON(1,I)
   50    CONTINUE
         NACTMX = MAX(NACTMX, NACT)
         IF (MOD(ISTEP, 20) .EQ. 0) WRITE (6, 1000) ISTEP, T, X(1,2),
     &      V(1,2), FX, NACT
  100 CONTINUE
      CALL EXIC_CONTACT_FREE(IH, IERR)
      IF (IERR .NE. 0) GOTO 900
      WRITE (6, 1010) PENMAX, NACTMX, V(1,1)
      STOP
C
  900 CALL EXIC_CONTACT_ERROR_MESSAGE(IH, MSG, LMSG, IERR)
      WRITE (6, '(A,A)') ' SKELETON: ', MSG(1:LMSG)
      STOP 1
 1000 FORMAT (' STEP', I5, '  T', F8.4, '  X2', F10.6, '  VX2', F10.6,
     &        '  FCON', 1PE12.4, '  ACTIVE', I3)
 1010 FORMAT (' SKELETON: LARGEST PENETRATION', 1PE10.2,
     &        '  MOST CONSTRAINTS', I3, '  FINAL VX1', 0PF8.4)
      END
C
C     SPRING FORCES F OF THE SQUARE (STIFFNESS 100, REST LENGTHS FROM
C     X0) AND A = F / M; THE BLOCK'S DOFS ARE FIXED (A = 0).
      SUBROUTINE SPRING(NN, X0, X, AM, IFIX, F, A)
      IMPLICIT NONE
      INTEGER NN, IFIX(2,NN)
      DOUBLE PRECISION X0(2,NN), X(2,NN), AM(NN), F(2,NN), A(2,NN)
      INTEGER IS(2,6), J, K, I1, I2
      DOUBLE PRECISION D(2), D0(2), RL, RL0, S
      DATA IS / 1,2, 2,3, 3,4, 4,1, 1,3, 2,4 /
      DO 10 J = 1, NN
         F(1,J) = 0.0D0
         F(2,J) = 0.0D0
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
         S = 100.0D0*(RL - RL0)/RL
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
