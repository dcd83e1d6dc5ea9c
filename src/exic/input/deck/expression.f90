!> Numeric expressions of deck fields and the parameter table (input language, section 1).
!>
!> Grammar (no blanks inside an expression):
!>
!>     expr    = term { ("+"|"-") term }
!>     term    = unary { ("*"|"/") unary }
!>     unary   = ("+"|"-") unary | power
!>     power   = primary { "^" signed }          ! left to right, as FEAP: 2^3^2 = 64
!>     signed  = ["+"|"-"] primary
!>     primary = number | name | func "(" expr ")" | "(" expr ")"
!>
!> So `^` binds tighter than a unary minus (-2^2 = -4) and `2^-1` = 0.5. Parentheses may nest
!> (FEAP allows one level). Numbers take an exponent only with `e` or `d`: `1.0+3` is 4.
!> Functions: sqrt sin cos tan asin acos atan exp log abs int sinh cosh tanh, and the degree
!> forms sind cosd tand asind acosd atand. Parameter names have up to 16 characters (letters,
!> digits, `_`, starting with a letter) and are case-folded.
module exic_input_deck_expression
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, to_lower
   use exic_base_error, only: error_t, make_error
   use exic_base_grow, only: grow
   implicit none
   private

   public :: param_table_t, set_param, get_param, evaluate, is_valid_name

   !> Longest parameter name.
   integer, parameter, public :: MAX_NAME = 16

   !> Parameters defined by PARAmeter records.
   type :: param_table_t
      integer :: n = 0
      character(len=MAX_NAME), allocatable :: name(:)
      real(wp), allocatable :: value(:)
   end type param_table_t

   !> Parse state: the text, the position of the next character, and the first problem found.
   type :: parser_t
      character(len=:), allocatable :: s
      integer :: p = 1
      character(len=:), allocatable :: msg
   end type parser_t

   real(wp), parameter :: deg = acos(-1.0_wp)/180.0_wp

contains

   !> True when `name` is a valid parameter name.
   pure logical function is_valid_name(name)
      character(len=*), intent(in) :: name
      integer :: k
      is_valid_name = len(name) >= 1 .and. len(name) <= MAX_NAME
      if (.not. is_valid_name) return
      is_valid_name = is_letter(name(1:1))
      do k = 2, len(name)
         if (.not. (is_letter(name(k:k)) .or. is_digit(name(k:k)) .or. name(k:k) == '_')) &
            is_valid_name = .false.
      end do
   end function is_valid_name

   !> Define or redefine parameter `name` (case-folded).
   pure subroutine set_param(tab, name, value)
      type(param_table_t), intent(inout) :: tab
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: value
      integer :: k
      do k = 1, tab%n
         if (tab%name(k) == to_lower(name)) then
            tab%value(k) = value
            return
         end if
      end do
      call grow(tab%name, tab%n + 1)
      call grow(tab%value, tab%n + 1)
      tab%n = tab%n + 1
      tab%name(tab%n) = to_lower(name)
      tab%value(tab%n) = value
   end subroutine set_param

   !> Look up parameter `name`; `found` is false when it is not defined.
   pure subroutine get_param(tab, name, value, found)
      type(param_table_t), intent(in) :: tab
      character(len=*), intent(in) :: name
      real(wp), intent(out) :: value
      logical, intent(out) :: found
      integer :: k
      value = 0.0_wp
      found = .false.
      if (len(name) > MAX_NAME) return
      do k = 1, tab%n
         if (tab%name(k) == to_lower(name)) then
            value = tab%value(k)
            found = .true.
            return
         end if
      end do
   end subroutine get_param

   !> Evaluate `text` with the parameters of `tab`. An empty text is 0. On failure `err` says
   !> what was expected, prefixed by `file:line` when given.
   subroutine evaluate(text, tab, value, err, file, line)
      character(len=*), intent(in) :: text
      type(param_table_t), intent(in) :: tab
      real(wp), intent(out) :: value
      type(error_t), allocatable, intent(out) :: err
      character(len=*), intent(in), optional :: file
      integer, intent(in), optional :: line
      type(parser_t) :: ps

      value = 0.0_wp
      if (len_trim(text) == 0) return
      ps%s = trim(adjustl(text))
      ps%p = 1
      call parse_expr(ps, tab, value)
      if (.not. allocated(ps%msg) .and. ps%p <= len(ps%s)) then
         if (ps%s(ps%p:ps%p) == ')') then
            ps%msg = 'unbalanced parentheses: expected no ")" at position '//itoa(ps%p)
         else
            ps%msg = 'expected an operator at "'//ps%s(ps%p:)//'"'
         end if
      end if
      if (.not. allocated(ps%msg)) then
         if (value /= value .or. abs(value) > huge(1.0_wp)) ps%msg = 'result is not a finite number'
      end if
      if (allocated(ps%msg)) then
         value = 0.0_wp
         call make_error(err, 'in expression "'//ps%s//'": '//ps%msg, file, line)
      end if
   end subroutine evaluate

   recursive subroutine parse_expr(ps, tab, v)
      type(parser_t), intent(inout) :: ps
      type(param_table_t), intent(in) :: tab
      real(wp), intent(out) :: v
      real(wp) :: w
      character :: op
      call parse_term(ps, tab, v)
      do while (.not. allocated(ps%msg) .and. ps%p <= len(ps%s))
         op = ps%s(ps%p:ps%p)
         if (op /= '+' .and. op /= '-') exit
         ps%p = ps%p + 1
         call parse_term(ps, tab, w)
         if (op == '+') then
            v = v + w
         else
            v = v - w
         end if
      end do
   end subroutine parse_expr

   recursive subroutine parse_term(ps, tab, v)
      type(parser_t), intent(inout) :: ps
      type(param_table_t), intent(in) :: tab
      real(wp), intent(out) :: v
      real(wp) :: w
      character :: op
      call parse_unary(ps, tab, v)
      do while (.not. allocated(ps%msg) .and. ps%p <= len(ps%s))
         op = ps%s(ps%p:ps%p)
         if (op /= '*' .and. op /= '/') exit
         ps%p = ps%p + 1
         call parse_unary(ps, tab, w)
         if (allocated(ps%msg)) return
         if (op == '*') then
            v = v*w
         else if (w == 0.0_wp) then
            ps%msg = 'division by zero'
         else
            v = v/w
         end if
      end do
   end subroutine parse_term

   recursive subroutine parse_unary(ps, tab, v)
      type(parser_t), intent(inout) :: ps
      type(param_table_t), intent(in) :: tab
      real(wp), intent(out) :: v
      character :: op
      v = 0.0_wp
      if (ps%p > len(ps%s)) then
         ps%msg = 'expected a number, parameter or "(" at the end'
         return
      end if
      op = ps%s(ps%p:ps%p)
      if (op == '+' .or. op == '-') then
         ps%p = ps%p + 1
         call parse_unary(ps, tab, v)
         if (op == '-') v = -v
      else
         call parse_power(ps, tab, v)
      end if
   end subroutine parse_unary

   recursive subroutine parse_power(ps, tab, v)
      type(parser_t), intent(inout) :: ps
      type(param_table_t), intent(in) :: tab
      real(wp), intent(out) :: v
      real(wp) :: w
      character :: op
      call parse_primary(ps, tab, v)
      do while (.not. allocated(ps%msg) .and. ps%p <= len(ps%s))
         if (ps%s(ps%p:ps%p) /= '^') exit
         ps%p = ps%p + 1
         op = ' '
         if (ps%p <= len(ps%s)) op = ps%s(ps%p:ps%p)
         if (op == '+' .or. op == '-') ps%p = ps%p + 1
         call parse_primary(ps, tab, w)
         if (allocated(ps%msg)) return
         if (op == '-') w = -w
         if (v < 0.0_wp .and. w /= aint(w)) then
            ps%msg = 'negative number to a non-integer power'
         else if (v == 0.0_wp .and. w < 0.0_wp) then
            ps%msg = 'zero to a negative power'
         else if (w == aint(w) .and. abs(w) < 1.0e9_wp) then
            v = v**nint(w)
         else
            v = v**w
         end if
      end do
   end subroutine parse_power

   recursive subroutine parse_primary(ps, tab, v)
      type(parser_t), intent(inout) :: ps
      type(param_table_t), intent(in) :: tab
      real(wp), intent(out) :: v
      character :: c
      integer :: q
      character(len=:), allocatable :: name
      logical :: found

      v = 0.0_wp
      if (ps%p > len(ps%s)) then
         ps%msg = 'expected a number, parameter or "(" at the end'
         return
      end if
      c = ps%s(ps%p:ps%p)
      if (c == '(') then
         ps%p = ps%p + 1
         call parse_expr(ps, tab, v)
         call close_paren(ps)
      else if (is_digit(c) .or. c == '.') then
         call parse_number(ps, v)
      else if (is_letter(c)) then
         q = ps%p
         do while (q <= len(ps%s))
            c = ps%s(q:q)
            if (.not. (is_letter(c) .or. is_digit(c) .or. c == '_')) exit
            q = q + 1
         end do
         name = to_lower(ps%s(ps%p:q - 1))
         ps%p = q
         if (q <= len(ps%s)) then
            if (ps%s(q:q) == '(') then
               ps%p = q + 1
               call parse_expr(ps, tab, v)
               call close_paren(ps)
               if (.not. allocated(ps%msg)) call apply_function(ps, name, v)
               return
            end if
         end if
         if (len(name) > MAX_NAME) then
            ps%msg = 'parameter name "'//name//'" is too long: expected at most 16 characters'
            return
         end if
         call get_param(tab, name, v, found)
         if (.not. found) ps%msg = 'undefined parameter "'//name//'": expected it in a PARAmeter set'
      else if (c == ')') then
         ps%msg = 'unbalanced parentheses: expected a value before ")"'
      else
         ps%msg = 'expected a number, parameter or "(" at "'//ps%s(ps%p:)//'"'
      end if
   end subroutine parse_primary

   subroutine close_paren(ps)
      type(parser_t), intent(inout) :: ps
      if (allocated(ps%msg)) return
      if (ps%p > len(ps%s)) then
         ps%msg = 'unbalanced parentheses: expected ")"'
      else if (ps%s(ps%p:ps%p) /= ')') then
         ps%msg = 'expected ")" at "'//ps%s(ps%p:)//'"'
      else
         ps%p = ps%p + 1
      end if
   end subroutine close_paren

   !> digits [. digits] [(e|d) [+|-] digits]
   subroutine parse_number(ps, v)
      type(parser_t), intent(inout) :: ps
      real(wp), intent(out) :: v
      integer :: q, n, ios
      logical :: digits
      character(len=:), allocatable :: t

      n = len(ps%s)
      q = ps%p
      digits = .false.
      do while (q <= n)
         if (.not. is_digit(ps%s(q:q))) exit
         q = q + 1
         digits = .true.
      end do
      if (q <= n) then
         if (ps%s(q:q) == '.') then
            q = q + 1
            do while (q <= n)
               if (.not. is_digit(ps%s(q:q))) exit
               q = q + 1
               digits = .true.
            end do
         end if
      end if
      v = 0.0_wp
      if (.not. digits) then
         ps%msg = 'expected a number at "'//ps%s(ps%p:)//'"'
         return
      end if
      if (q <= n) then
         if (scan(ps%s(q:q), 'eEdD') > 0) then
            q = q + 1
            if (q <= n) then
               if (ps%s(q:q) == '+' .or. ps%s(q:q) == '-') q = q + 1
            end if
            if (q > n) then
               ps%msg = 'expected exponent digits at the end of "'//ps%s(ps%p:)//'"'
               return
            end if
            if (.not. is_digit(ps%s(q:q))) then
               ps%msg = 'expected exponent digits in "'//ps%s(ps%p:)//'"'
               return
            end if
            do while (q <= n)
               if (.not. is_digit(ps%s(q:q))) exit
               q = q + 1
            end do
         end if
      end if
      if (q <= n) then
         if (is_letter(ps%s(q:q)) .or. ps%s(q:q) == '.' .or. ps%s(q:q) == '_') then
            ps%msg = 'expected an operator after the number at "'//ps%s(ps%p:)//'"'
            return
         end if
      end if
      t = ps%s(ps%p:q - 1)
      do n = 1, len(t)
         if (t(n:n) == 'd' .or. t(n:n) == 'D') t(n:n) = 'e'
      end do
      read (t, *, iostat=ios) v
      if (ios /= 0) ps%msg = 'expected a number at "'//t//'"'
      ps%p = q
   end subroutine parse_number

   subroutine apply_function(ps, name, v)
      type(parser_t), intent(inout) :: ps
      character(len=*), intent(in) :: name
      real(wp), intent(inout) :: v
      select case (name)
      case ('sqrt')
         if (v < 0.0_wp) then
            ps%msg = 'sqrt of a negative number'
         else
            v = sqrt(v)
         end if
      case ('log')
         if (v <= 0.0_wp) then
            ps%msg = 'log of a non-positive number'
         else
            v = log(v)
         end if
      case ('exp')
         v = exp(v)
      case ('abs')
         v = abs(v)
      case ('int')
         v = aint(v)
      case ('sin')
         v = sin(v)
      case ('cos')
         v = cos(v)
      case ('tan')
         v = tan(v)
      case ('atan')
         v = atan(v)
      case ('asin', 'acos', 'asind', 'acosd')
         if (abs(v) > 1.0_wp) then
            ps%msg = name//' of a number outside [-1, 1]'
         else if (name == 'asin') then
            v = asin(v)
         else if (name == 'acos') then
            v = acos(v)
         else if (name == 'asind') then
            v = asin(v)/deg
         else
            v = acos(v)/deg
         end if
      case ('sinh')
         v = sinh(v)
      case ('cosh')
         v = cosh(v)
      case ('tanh')
         v = tanh(v)
      case ('sind')
         v = sin(v*deg)
      case ('cosd')
         v = cos(v*deg)
      case ('tand')
         v = tan(v*deg)
      case ('atand')
         v = atan(v)/deg
      case default
         ps%msg = 'unknown function "'//name//'": expected one of sqrt sin cos tan asin acos atan '// &
                  'exp log abs int sinh cosh tanh sind cosd tand asind acosd atand'
      end select
   end subroutine apply_function

   pure logical function is_digit(c)
      character, intent(in) :: c
      is_digit = c >= '0' .and. c <= '9'
   end function is_digit

   pure logical function is_letter(c)
      character, intent(in) :: c
      is_letter = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z')
   end function is_letter

end module exic_input_deck_expression
