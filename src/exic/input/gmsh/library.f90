!> The C API of the Gmsh library (`gmshc.h` of Debian's libgmsh-dev 4.8), loaded at run time.
!>
!> exic does not link libgmsh: relocating it and its ~120 dependencies (OpenCASCADE, FLTK, X11,
!> ...) cost every run about 0.11 s of processor time before `main`, whether the deck reads a
!> Gmsh mesh or not (doc/performance.md section 6.5). `gmsh_library_load` opens the library with
!> glibc's dlopen the first time a GMSH record is read and resolves every call below with dlsym;
!> the library then stays loaded for the rest of the process (never dlclose'd: its static
!> destructors run at exit as for a linked library). Flags RTLD_NOW | RTLD_LOCAL: every symbol
!> of Gmsh and its dependencies is bound at load, so a broken installation is an error of the
!> load, never a crash inside a later call; its symbols stay out of the global namespace, so
!> they cannot bind symbols of libraries loaded later (HDF5 plugins) or of the program.
!> Library names are the fixed list GMSH_LIBRARIES (nothing of a deck goes to dlopen).
!>
!> The Gmsh calls keep their C names; each is a procedure pointer (protected: set only here)
!> with the call's interface, associated by a successful `gmsh_library_load` and null before:
!> call that first (exic_input_gmsh does). Every call takes `ierr` last (0 on success); arrays the
!> library returns are allocated by it and must be released with `gmshFree`. `const int`,
!> `const double` and `const size_t` arguments are passed by value, strings as null-terminated
!> `character(kind=c_char)` arrays. Use exic_input_gmsh, which owns the library's state and turns
!> status codes into errors, rather than these directly.
module exic_input_gmsh_library
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_char, c_ptr, c_funptr, &
                                          c_null_char, c_associated, c_f_procpointer
   use exic_base_error, only: error_t, make_error
   use exic_base_posix, only: c_string
   implicit none
   private

   public :: GMSH_LIBRARIES, gmsh_library_load, gmsh_library_open
   public :: gmshInitialize, gmshFinalize, gmshOpen, gmshFree, gmshOptionSetNumber
   public :: gmshModelGetEntities, gmshModelGetPhysicalGroups, gmshModelGetPhysicalName
   public :: gmshModelGetEntitiesForPhysicalGroup, gmshModelGetPhysicalGroupsForEntity
   public :: gmshModelMeshGenerate, gmshModelMeshGetNodes, gmshModelMeshGetElementTypes
   public :: gmshModelMeshGetElementsByType, gmshModelMeshGetElementProperties
   public :: gmshLoggerStart, gmshLoggerStop, gmshLoggerGet, gmshLoggerGetLastError

   !> The names dlopen tries, in order: the soname a link with -lgmsh records on Debian 12
   !> (libgmsh4.8, the C API these interfaces follow; the test suite checks it against the
   !> SONAME of the installed libgmsh.so), then the development link libgmsh.so.
   character(len=*), parameter :: GMSH_LIBRARIES(2) = [character(len=14) :: 'libgmsh.so.4.8', &
                                                       'libgmsh.so']

   !> dlopen flags of glibc's <dlfcn.h> (bits/dlfcn.h): bind every symbol at load, keep them
   !> out of the global namespace.
   integer(c_int), parameter :: RTLD_NOW = 2, RTLD_LOCAL = 0

   interface
      !> void *dlopen(const char *filename, int flags)
      function dlopen(filename, flags) bind(C, name='dlopen') result(handle)
         import :: c_char, c_int, c_ptr
         character(kind=c_char), intent(in) :: filename(*)
         integer(c_int), value, intent(in) :: flags
         type(c_ptr) :: handle
      end function dlopen

      !> void *dlsym(void *handle, const char *symbol) (a function's address here)
      function dlsym(handle, symbol) bind(C, name='dlsym') result(address)
         import :: c_char, c_ptr, c_funptr
         type(c_ptr), value, intent(in) :: handle
         character(kind=c_char), intent(in) :: symbol(*)
         type(c_funptr) :: address
      end function dlsym

      !> char *dlerror(void): the last dl* error of this thread, or NULL
      function dlerror() bind(C, name='dlerror') result(message)
         import :: c_ptr
         type(c_ptr) :: message
      end function dlerror
   end interface

   abstract interface


      !> void gmshInitialize(int argc, char **argv, const int readConfigFiles, int *ierr)
      subroutine gmshInitialize_i(argc, argv, readConfigFiles, ierr) bind(C)
         import :: c_int, c_ptr
         integer(c_int), value, intent(in) :: argc
         type(c_ptr), value, intent(in) :: argv
         integer(c_int), value, intent(in) :: readConfigFiles
         integer(c_int), intent(out) :: ierr
      end subroutine gmshInitialize_i

      !> void gmshFinalize(int *ierr)
      subroutine gmshFinalize_i(ierr) bind(C)
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshFinalize_i

      !> void gmshOpen(const char *fileName, int *ierr)
      subroutine gmshOpen_i(fileName, ierr) bind(C)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: fileName(*)
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOpen_i

      !> void gmshFree(void *p)
      subroutine gmshFree_i(p) bind(C)
         import :: c_ptr
         type(c_ptr), value, intent(in) :: p
      end subroutine gmshFree_i

      !> void gmshOptionSetNumber(const char *name, const double value, int *ierr)
      subroutine gmshOptionSetNumber_i(name, value, ierr) bind(C)
         import :: c_int, c_char, c_double
         character(kind=c_char), intent(in) :: name(*)
         real(c_double), value, intent(in) :: value
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOptionSetNumber_i

      !> void gmshModelGetEntities(int **dimTags, size_t *dimTags_n, const int dim, int *ierr)
      subroutine gmshModelGetEntities_i(dimTags, dimTags_n, dim, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: dimTags
         integer(c_size_t), intent(out) :: dimTags_n
         integer(c_int), value, intent(in) :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetEntities_i

      !> void gmshModelGetPhysicalGroups(int **dimTags, size_t *dimTags_n, const int dim,
      !> int *ierr)
      subroutine gmshModelGetPhysicalGroups_i(dimTags, dimTags_n, dim, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: dimTags
         integer(c_size_t), intent(out) :: dimTags_n
         integer(c_int), value, intent(in) :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalGroups_i

      !> void gmshModelGetEntitiesForPhysicalGroup(const int dim, const int tag, int **tags,
      !> size_t *tags_n, int *ierr)
      subroutine gmshModelGetEntitiesForPhysicalGroup_i(dim, tag, tags, tags_n, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: dim, tag
         type(c_ptr), intent(out) :: tags
         integer(c_size_t), intent(out) :: tags_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetEntitiesForPhysicalGroup_i

      !> void gmshModelGetPhysicalGroupsForEntity(const int dim, const int tag,
      !> int **physicalTags, size_t *physicalTags_n, int *ierr)
      subroutine gmshModelGetPhysicalGroupsForEntity_i(dim, tag, physicalTags, physicalTags_n, &
                                                     ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: dim, tag
         type(c_ptr), intent(out) :: physicalTags
         integer(c_size_t), intent(out) :: physicalTags_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalGroupsForEntity_i

      !> void gmshModelGetPhysicalName(const int dim, const int tag, char **name, int *ierr)
      subroutine gmshModelGetPhysicalName_i(dim, tag, name, ierr) &
         bind(C)
         import :: c_int, c_ptr
         integer(c_int), value, intent(in) :: dim, tag
         type(c_ptr), intent(out) :: name
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalName_i

      !> void gmshModelMeshGenerate(const int dim, int *ierr)
      subroutine gmshModelMeshGenerate_i(dim, ierr) bind(C)
         import :: c_int
         integer(c_int), value, intent(in) :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGenerate_i

      !> void gmshModelMeshGetNodes(size_t **nodeTags, size_t *nodeTags_n, double **coord,
      !> size_t *coord_n, double **parametricCoord, size_t *parametricCoord_n, const int dim,
      !> const int tag, const int includeBoundary, const int returnParametricCoord, int *ierr)
      subroutine gmshModelMeshGetNodes_i(nodeTags, nodeTags_n, coord, coord_n, parametricCoord, &
                                       parametricCoord_n, dim, tag, includeBoundary, &
                                       returnParametricCoord, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: nodeTags, coord, parametricCoord
         integer(c_size_t), intent(out) :: nodeTags_n, coord_n, parametricCoord_n
         integer(c_int), value, intent(in) :: dim, tag, includeBoundary, returnParametricCoord
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetNodes_i

      !> void gmshModelMeshGetElementTypes(int **elementTypes, size_t *elementTypes_n,
      !> const int dim, const int tag, int *ierr)
      subroutine gmshModelMeshGetElementTypes_i(elementTypes, elementTypes_n, dim, tag, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: elementTypes
         integer(c_size_t), intent(out) :: elementTypes_n
         integer(c_int), value, intent(in) :: dim, tag
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementTypes_i

      !> void gmshModelMeshGetElementsByType(const int elementType, size_t **elementTags,
      !> size_t *elementTags_n, size_t **nodeTags, size_t *nodeTags_n, const int tag,
      !> const size_t task, const size_t numTasks, int *ierr)
      subroutine gmshModelMeshGetElementsByType_i(elementType, elementTags, elementTags_n, &
                                                nodeTags, nodeTags_n, tag, task, numTasks, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: elementType
         type(c_ptr), intent(out) :: elementTags, nodeTags
         integer(c_size_t), intent(out) :: elementTags_n, nodeTags_n
         integer(c_int), value, intent(in) :: tag
         integer(c_size_t), value, intent(in) :: task, numTasks
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementsByType_i

      !> void gmshModelMeshGetElementProperties(const int elementType, char **elementName,
      !> int *dim, int *order, int *numNodes, double **localNodeCoord,
      !> size_t *localNodeCoord_n, int *numPrimaryNodes, int *ierr)
      subroutine gmshModelMeshGetElementProperties_i(elementType, elementName, dim, order, &
                                                   numNodes, localNodeCoord, localNodeCoord_n, &
                                                   numPrimaryNodes, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: elementType
         type(c_ptr), intent(out) :: elementName
         integer(c_int), intent(out) :: dim, order, numNodes
         type(c_ptr), intent(out) :: localNodeCoord
         integer(c_size_t), intent(out) :: localNodeCoord_n
         integer(c_int), intent(out) :: numPrimaryNodes
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementProperties_i

      !> void gmshLoggerStart(int *ierr)
      subroutine gmshLoggerStart_i(ierr) bind(C)
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerStart_i

      !> void gmshLoggerStop(int *ierr)
      subroutine gmshLoggerStop_i(ierr) bind(C)
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerStop_i

      !> void gmshLoggerGet(char ***log, size_t *log_n, int *ierr)
      subroutine gmshLoggerGet_i(log, log_n, ierr) bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: log
         integer(c_size_t), intent(out) :: log_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerGet_i

      !> void gmshLoggerGetLastError(char **error, int *ierr)
      subroutine gmshLoggerGetLastError_i(error, ierr) bind(C)
         import :: c_int, c_ptr
         type(c_ptr), intent(out) :: error
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerGetLastError_i

   end interface

   procedure(gmshInitialize_i), pointer, protected :: &
      gmshInitialize => null()
   procedure(gmshFinalize_i), pointer, protected :: &
      gmshFinalize => null()
   procedure(gmshOpen_i), pointer, protected :: &
      gmshOpen => null()
   procedure(gmshFree_i), pointer, protected :: &
      gmshFree => null()
   procedure(gmshOptionSetNumber_i), pointer, protected :: &
      gmshOptionSetNumber => null()
   procedure(gmshModelGetEntities_i), pointer, protected :: &
      gmshModelGetEntities => null()
   procedure(gmshModelGetPhysicalGroups_i), pointer, protected :: &
      gmshModelGetPhysicalGroups => null()
   procedure(gmshModelGetEntitiesForPhysicalGroup_i), pointer, protected :: &
      gmshModelGetEntitiesForPhysicalGroup => null()
   procedure(gmshModelGetPhysicalGroupsForEntity_i), pointer, protected :: &
      gmshModelGetPhysicalGroupsForEntity => null()
   procedure(gmshModelGetPhysicalName_i), pointer, protected :: &
      gmshModelGetPhysicalName => null()
   procedure(gmshModelMeshGenerate_i), pointer, protected :: &
      gmshModelMeshGenerate => null()
   procedure(gmshModelMeshGetNodes_i), pointer, protected :: &
      gmshModelMeshGetNodes => null()
   procedure(gmshModelMeshGetElementTypes_i), pointer, protected :: &
      gmshModelMeshGetElementTypes => null()
   procedure(gmshModelMeshGetElementsByType_i), pointer, protected :: &
      gmshModelMeshGetElementsByType => null()
   procedure(gmshModelMeshGetElementProperties_i), pointer, protected :: &
      gmshModelMeshGetElementProperties => null()
   procedure(gmshLoggerStart_i), pointer, protected :: &
      gmshLoggerStart => null()
   procedure(gmshLoggerStop_i), pointer, protected :: &
      gmshLoggerStop => null()
   procedure(gmshLoggerGet_i), pointer, protected :: &
      gmshLoggerGet => null()
   procedure(gmshLoggerGetLastError_i), pointer, protected :: &
      gmshLoggerGetLastError => null()

   !> The library's handle once loaded.
   type(c_ptr), save :: library
   logical, save :: loaded = .false.

contains

   !> Load the Gmsh library (the first of `names` that dlopen opens) and resolve every call of
   !> this module; once loaded, further calls return at once. `err` names the libraries tried
   !> with dlerror's text for each, or the call the library lacks; the caller adds where.
   subroutine gmsh_library_load(names, err)
      character(len=*), intent(in) :: names(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: handle
      character(len=:), allocatable :: missing, opened
      if (loaded) return
      call gmsh_library_open(names, handle, opened, err)
      if (allocated(err)) return
      missing = ''
      call c_f_procpointer(symbol('gmshInitialize'), gmshInitialize)
      call c_f_procpointer(symbol('gmshFinalize'), gmshFinalize)
      call c_f_procpointer(symbol('gmshOpen'), gmshOpen)
      call c_f_procpointer(symbol('gmshFree'), gmshFree)
      call c_f_procpointer(symbol('gmshOptionSetNumber'), gmshOptionSetNumber)
      call c_f_procpointer(symbol('gmshModelGetEntities'), gmshModelGetEntities)
      call c_f_procpointer(symbol('gmshModelGetPhysicalGroups'), gmshModelGetPhysicalGroups)
      call c_f_procpointer(symbol('gmshModelGetEntitiesForPhysicalGroup'), &
                           gmshModelGetEntitiesForPhysicalGroup)
      call c_f_procpointer(symbol('gmshModelGetPhysicalGroupsForEntity'), &
                           gmshModelGetPhysicalGroupsForEntity)
      call c_f_procpointer(symbol('gmshModelGetPhysicalName'), gmshModelGetPhysicalName)
      call c_f_procpointer(symbol('gmshModelMeshGenerate'), gmshModelMeshGenerate)
      call c_f_procpointer(symbol('gmshModelMeshGetNodes'), gmshModelMeshGetNodes)
      call c_f_procpointer(symbol('gmshModelMeshGetElementTypes'), gmshModelMeshGetElementTypes)
      call c_f_procpointer(symbol('gmshModelMeshGetElementsByType'), gmshModelMeshGetElementsByType)
      call c_f_procpointer(symbol('gmshModelMeshGetElementProperties'), &
                           gmshModelMeshGetElementProperties)
      call c_f_procpointer(symbol('gmshLoggerStart'), gmshLoggerStart)
      call c_f_procpointer(symbol('gmshLoggerStop'), gmshLoggerStop)
      call c_f_procpointer(symbol('gmshLoggerGet'), gmshLoggerGet)
      call c_f_procpointer(symbol('gmshLoggerGetLastError'), gmshLoggerGetLastError)
      if (len(missing) > 0) then
         call make_error(err, 'the Gmsh library '//opened//' lacks'//missing// &
                         ': expected the C API of Gmsh 4.8 (Debian 12: libgmsh-dev)')
         return
      end if
      library = handle
      loaded = .true.
   contains
      !> The address of `name` in the library; a missing one is added to `missing`.
      function symbol(name) result(address)
         character(len=*), intent(in) :: name
         type(c_funptr) :: address
         type(c_ptr) :: msg
         msg = dlerror()
         address = dlsym(handle, name//c_null_char)
         msg = dlerror()
         if (c_associated(msg)) missing = missing//' '//name//' ('//c_string(msg)//')'
      end function symbol
   end subroutine gmsh_library_load

   !> dlopen the first of `names` that opens (RTLD_NOW | RTLD_LOCAL) into `handle`, `opened`
   !> its name. Keeps no state: with none opening, `err` lists every name with dlerror's text.
   subroutine gmsh_library_open(names, handle, opened, err)
      character(len=*), intent(in) :: names(:)
      type(c_ptr), intent(out) :: handle
      character(len=:), allocatable, intent(out) :: opened
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: tried
      integer :: k
      tried = ''
      do k = 1, size(names)
         handle = dlopen(trim(names(k))//c_null_char, ior(RTLD_NOW, RTLD_LOCAL))
         if (c_associated(handle)) then
            opened = trim(names(k))
            return
         end if
         if (k > 1) tried = tried//'; '
         tried = tried//trim(names(k))//': '//c_string(dlerror())
      end do
      opened = ''
      call make_error(err, 'the Gmsh library could not be loaded (tried '//tried// &
                      '): expected Gmsh 4.8''s shared library (Debian 12: apt-get install '// &
                      'libgmsh-dev, which `make deps` does)')
   end subroutine gmsh_library_open

end module exic_input_gmsh_library
