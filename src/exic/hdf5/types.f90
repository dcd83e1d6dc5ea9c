!> Element types of the datasets exic writes with HDF5 (DTYPE_*), their file and memory types,
!> and the fill values of dataset creation lists: shared by exic_hdf5_file and
!> exic_hdf5_held.
module exic_hdf5_types
   use, intrinsic :: iso_c_binding, only: c_loc
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use exic_base_kinds, only: wp, i8
   use hdf5, only: hid_t, h5pset_fill_value_f, h5kind_to_type, H5_REAL_KIND, H5_INTEGER_KIND, &
                   H5T_IEEE_F64LE, H5T_STD_I32LE, H5T_STD_I64LE
   implicit none
   private

   public :: DTYPE_REAL, DTYPE_INT, DTYPE_INT64, file_type, mem_type, elem_bytes, set_zero_fill, &
             set_unwritten_fill

   !> Element types of datasets: real(wp) (IEEE 64-bit), default integer (32-bit), integer(i8).
   integer, parameter :: DTYPE_REAL = 1, DTYPE_INT = 2, DTYPE_INT64 = 3

contains

   !> Set the fill value of the dataset creation list `dcpl` to what an unwritten slab of a
   !> preallocated series reads as: NaN for reals, -1 for integers.
   subroutine set_unwritten_fill(dcpl, dtype, st)
      integer(hid_t), intent(in) :: dcpl
      integer, intent(in) :: dtype
      integer, intent(out) :: st
      real(wp), target :: nan
      integer(i8), target :: minus_one_i8
      integer, target :: minus_one
      nan = ieee_value(0.0_wp, ieee_quiet_nan)
      minus_one_i8 = -1
      minus_one = -1
      select case (dtype)
      case (DTYPE_REAL)
         call h5pset_fill_value_f(dcpl, mem_type(dtype), c_loc(nan), st)
      case (DTYPE_INT64)
         call h5pset_fill_value_f(dcpl, mem_type(dtype), c_loc(minus_one_i8), st)
      case default
         call h5pset_fill_value_f(dcpl, mem_type(DTYPE_INT), c_loc(minus_one), st)
      end select
   end subroutine set_unwritten_fill

   !> Set the fill value of the dataset creation list `dcpl` to zero of type `dtype`.
   subroutine set_zero_fill(dcpl, dtype, st)
      integer(hid_t), intent(in) :: dcpl
      integer, intent(in) :: dtype
      integer, intent(out) :: st
      select case (dtype)
      case (DTYPE_REAL)
         call h5pset_fill_value_f(dcpl, mem_type(dtype), 0.0_wp, st)
      case default
         call h5pset_fill_value_f(dcpl, mem_type(DTYPE_INT), 0, st)
      end select
   end subroutine set_zero_fill

   !> HDF5 type stored in the file for `dtype` (little-endian IEEE / two's complement).
   function file_type(dtype) result(t)
      integer, intent(in) :: dtype
      integer(hid_t) :: t
      select case (dtype)
      case (DTYPE_REAL)
         t = H5T_IEEE_F64LE
      case (DTYPE_INT64)
         t = H5T_STD_I64LE
      case default
         t = H5T_STD_I32LE
      end select
   end function file_type

   !> HDF5 memory type of `dtype` as Fortran holds it.
   function mem_type(dtype) result(t)
      integer, intent(in) :: dtype
      integer(hid_t) :: t
      select case (dtype)
      case (DTYPE_REAL)
         t = h5kind_to_type(wp, H5_REAL_KIND)
      case (DTYPE_INT64)
         t = h5kind_to_type(i8, H5_INTEGER_KIND)
      case default
         t = h5kind_to_type(kind(0), H5_INTEGER_KIND)
      end select
   end function mem_type

   !> Bytes of one element of `dtype` in the file.
   pure integer(i8) function elem_bytes(dtype)
      integer, intent(in) :: dtype
      select case (dtype)
      case (DTYPE_INT)
         elem_bytes = 4
      case default
         elem_bytes = 8
      end select
   end function elem_bytes
end module exic_hdf5_types
