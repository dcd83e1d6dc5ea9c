!> The health of the state after a step (explicit/step.f90, step 7): a non-finite value stops
!> the run naming its node and an element; the energy guard warns and stops on energy growth
!> (doc/decisions.md, "Energy guard").
submodule(exic_explicit_step) exic_explicit_step_health
   implicit none

contains

   !> Stop on a non-finite value, naming where it first appears; the energy guard.
   !>
   !> E = kinetic + strain + hourglass + plastic work (doc/axisymmetry.md, (A13)) (+ the frictional
   !> dissipation, energy that left, with friction: doc/friction.md section 5), E_in = E(0) + W_ext +
   !> W_pm (the energy put in, W_pm the
   !> work of the prescribed motion, doc/loads.md section 3),
   !> growth = (E - E_in) / (|E(0)| + |W_ext| + |W_pm|): past energy_warn a warning (once), past
   !> energy_stop an error naming the largest contributor (doc/decisions.md, "Energy guard").
   module procedure check_health
      real(wp) :: e, put_in, growth, w_in, c, r
      character(len=:), allocatable :: what
      associate (st => self%st)
         if (self%contact%friction) st%energy%friction = self%contact%dissipation
         e = st%energy%physical()
         if (.not. (ieee_is_finite(e) .and. ieee_is_finite(st%energy%wext) .and. ieee_is_finite(st%energy%wcon))) then
            call decomposition_gather_nodes(self%dd, st)
            call make_error(err, 'a value is not finite at t = '//rtoa(st%t)//', step '// &
                            itoa(int(st%step))//': '//first_nonfinite(self))
            return
         end if
         ! frictional dissipation is energy that left the bodies (doc/friction.md, section 5)
         if (self%contact%friction) e = e + st%energy%friction
         if (self%ld%active) then
            ! loads and prescribed motion: the energy the scheme conserves, with the kinetic
            ! correction (doc/loads.md, section 3, eq. P.4), against the larger of two estimates
            ! of their work (loading.f90)
            e = e + kinetic_correction(st)
            ! the contact forces' part of it: the energy conserved across a closed contact
            ! (doc/loads.md, section 3, eq. P.5), where it lowers the measure; a rise is the
            ! one-step transient of a contact force that appears or vanishes (P.6)
            if (self%has_contact()) e = e + min(contact_correction(st), 0.0_wp)
            w_in = self%ld%work_in(st)
            put_in = abs(st%energy%total0) + max(abs(st%energy%wext) + abs(st%energy%wpm), abs(w_in))
         else
            w_in = st%energy%wext + st%energy%wpm
            put_in = abs(st%energy%total0) + abs(st%energy%wext) + abs(st%energy%wpm)
         end if
         ! energy put in below the round-off scale (none, or a round-off amount) is measured
         ! against that scale: energy that appears at the level of round-off is not growth
         put_in = max(put_in, self%energy_floor)
         if (put_in > 0.0_wp) then
            growth = (e - (st%energy%total0 + w_in))/put_in
         else
            growth = merge(huge(1.0_wp), 0.0_wp, e > 0.0_wp)
         end if
         if (growth > self%energy_warn .and. .not. self%ld%active .and. put_in > 0.0_wp) then
            ! past the warning limit, the energy the scheme conserves decides, H = E + C (eq. E.3,
            ! doc/decisions.md "Energy guard", (G1)-(G2)): an impulsive start (velocities given at
            ! single nodes) puts energy into the highest modes, where E exceeds H by dt^2/8 Q
            ! (20 % at step 1 on a 2x2 bar at CFL 0.9), which is not growth. H is conserved by
            ! an unstable step too (it is then indefinite), so it is taken only while
            ! E - H <= r^2 E, r = dt / dt_stable, which holds for every stable step (G2)
            c = kinetic_correction(st)
            if (self%dt_stable > 0.0_wp) then
               r = st%dt/self%dt_stable
               if (r < 1.0_wp .and. -c <= r*r*e) growth = (e + c - (st%energy%total0 + w_in))/put_in
            end if
         end if
         if (growth > self%growth_max) then
            self%growth_max = growth
            self%growth_max_t = st%t
         end if
         if (growth <= self%energy_warn) return
         if (put_in > self%energy_floor) then
            what = 'the physical energy (kinetic + strain + plastic work'//trim(merge(' + frictional dissipation', &
                   '                         ', self%contact%friction))//') exceeds the energy put in (initial energy '// &
                   '+ external work + work of prescribed motion) by '//percent(growth)//' of it at t = '// &
                   rtoa(st%t)//', step '//itoa(int(st%step))
         else
            what = 'kinetic + strain energy '//rtoa(e)//' appeared with no energy put in (round-off scale '// &
                   rtoa(self%energy_floor)//') at t = '//rtoa(st%t)//', step '//itoa(int(st%step))
         end if
         ! contributor reads every node: the whole state first (every rank is here at this step)
         if (growth > self%energy_stop .or. .not. self%energy_warned) call decomposition_gather_nodes(self%dd, st)
         if (growth > self%energy_stop) then
            call make_error(err, what//' (stop limit '//percent(self%energy_stop)//'); largest '// &
                            'contributor: '//contributor(self, put_in))
         else if (.not. self%energy_warned) then
            self%energy_warned = .true.
            call self%messages%add('warning: '//what//' (warning limit '//percent(self%energy_warn)// &
                                   '); largest contributor: '//contributor(self, put_in))
         end if
      end associate
   end procedure check_health

   !> A fraction as a percentage with three significant digits.
   function percent(x) result(text)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: text
      character(len=32) :: buf
      if (x >= huge(1.0_wp)/100.0_wp) then
         text = 'all'
      else
         if (abs(100.0_wp*x) < 1.0e99_wp .and. (x == 0.0_wp .or. abs(100.0_wp*x) >= 1.0e-99_wp)) then
            write (buf, '(es10.3)') 100.0_wp*x
         else
            write (buf, '(es11.3e3)') 100.0_wp*x
         end if
         text = trim(adjustl(buf))//' %'
      end if
   end function percent

   !> Where the energy grew most: the contact pair whose multipliers did the most positive work
   !> (pushing bodies apart), when that work is at least half the warning margin; else the
   !> element whose nodes carry the largest kinetic energy (a local instability shows there).
   function contributor(self, put_in) result(text)
      type(stepper_t), intent(in) :: self
      real(wp), intent(in) :: put_in
      character(len=:), allocatable :: text
      integer :: k, kbest, e, ebest, i, j
      real(wp) :: wbest, ek, ebig
      kbest = 0
      wbest = 0.0_wp
      if (self%contact%active) then
         do k = 1, size(self%contact%results)
            if (self%contact%results(k)%work > wbest) then
               wbest = self%contact%results(k)%work
               kbest = k
            end if
         end do
      end if
      ebest = 0
      ebig = -1.0_wp
      do k = 1, size(self%sets)
         do j = 1, self%sets(k)%nel
            ek = 0.0_wp
            do i = 1, 4
               associate (n => self%sets(k)%conn(i, j))
                  ek = ek + 0.5_wp*self%st%mass(n)*(self%st%v(1, n)**2 + self%st%v(2, n)**2)
               end associate
            end do
            if (ek > ebig) then
               ebig = ek
               ebest = self%sets(k)%elems(j)
            end if
         end do
      end do
      if (kbest > 0 .and. wbest > 0.5_wp*put_in*self%energy_warn) then
         text = 'contact pair '//itoa(self%contact%results(kbest)%id)//', whose multipliers did '// &
                rtoa(wbest)//' of work ('//percent(wbest/max(put_in, tiny(1.0_wp)))//' of the energy put in)'
      else
         e = ebest
         text = 'element '//itoa(e)//', whose nodes carry kinetic energy '//rtoa(ebig)//' ('// &
                percent(ebig/max(put_in, tiny(1.0_wp)))//' of the energy put in)'
      end if
   end function contributor

   !> The first node (and an element using it) whose displacement, velocity, acceleration,
   !> internal force or contact force is not finite.
   module procedure first_nonfinite
      integer :: i, k, j
      character(len=13) :: what
      text = 'no node has a non-finite value (the energy sums overflowed)'
      associate (st => self%st)
         do i = 1, st%nnode
            if (.not. all(ieee_is_finite(st%u(:, i)))) then
               what = 'displacement'
            else if (.not. all(ieee_is_finite(st%v(:, i)))) then
               what = 'velocity'
            else if (.not. all(ieee_is_finite(st%a(:, i)))) then
               what = 'acceleration'
            else if (.not. all(ieee_is_finite(st%fint(:, i)))) then
               what = 'force'
            else if (.not. all(ieee_is_finite(st%fcon(:, i)))) then
               what = 'contact force'
            else
               cycle
            end if
            text = 'the '//trim(what)//' of node '//itoa(i)
            do k = 1, size(self%sets)
               do j = 1, self%sets(k)%nel
                  if (any(self%sets(k)%conn(:, j) == i)) then
                     text = text//' (element '//itoa(self%sets(k)%elems(j))//')'
                     return
                  end if
               end do
            end do
            return
         end do
      end associate
   end procedure first_nonfinite

end submodule exic_explicit_step_health
