!> Raw bind(C) interfaces to the C API of the Gmsh library (`gmshc.h` of Debian's libgmsh-dev
!> 4.8; link with `-lgmsh`). Only the calls exic needs. Every call takes `ierr` last (0 on
!> success); arrays the library returns are allocated by it and must be released with
!> `gmshFree`. `const int`, `const double` and `const size_t` arguments are passed by value,
!> strings as null-terminated `character(kind=c_char)` arrays. Use exic_io_gmsh, which owns
!> the library's state and turns status codes into errors, rather than these directly.
module exic_io_gmsh_c
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_char, c_ptr
   implicit none
   private

   public :: gmshInitialize, gmshFinalize, gmshOpen, gmshFree, gmshOptionSetNumber
   public :: gmshModelGetEntities, gmshModelGetPhysicalGroups, gmshModelGetPhysicalName
   public :: gmshModelGetEntitiesForPhysicalGroup, gmshModelGetPhysicalGroupsForEntity
   public :: gmshModelMeshGenerate, gmshModelMeshGetNodes, gmshModelMeshGetElementTypes
   public :: gmshModelMeshGetElementsByType, gmshModelMeshGetElementProperties
   public :: gmshLoggerStart, gmshLoggerStop, gmshLoggerGet, gmshLoggerGetLastError

   interface

      !> void gmshInitialize(int argc, char **argv, const int readConfigFiles, int *ierr)
      subroutine gmshInitialize(argc, argv, readConfigFiles, ierr) bind(C, name='gmshInitialize')
         import :: c_int, c_ptr
         integer(c_int), value, intent(in) :: argc
         type(c_ptr), value, intent(in) :: argv
         integer(c_int), value, intent(in) :: readConfigFiles
         integer(c_int), intent(out) :: ierr
      end subroutine gmshInitialize

      !> void gmshFinalize(int *ierr)
      subroutine gmshFinalize(ierr) bind(C, name='gmshFinalize')
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshFinalize

      !> void gmshOpen(const char *fileName, int *ierr)
      subroutine gmshOpen(fileName, ierr) bind(C, name='gmshOpen')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: fileName(*)
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOpen

      !> void gmshFree(void *p)
      subroutine gmshFree(p) bind(C, name='gmshFree')
         import :: c_ptr
         type(c_ptr), value, intent(in) :: p
      end subroutine gmshFree

      !> void gmshOptionSetNumber(const char *name, const double value, int *ierr)
      subroutine gmshOptionSetNumber(name, value, ierr) bind(C, name='gmshOptionSetNumber')
         import :: c_int, c_char, c_double
         character(kind=c_char), intent(in) :: name(*)
         real(c_double), value, intent(in) :: value
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOptionSetNumber

      !> void gmshModelGetEntities(int **dimTags, size_t *dimTags_n, const int dim, int *ierr)
      subroutine gmshModelGetEntities(dimTags, dimTags_n, dim, ierr) &
         bind(C, name='gmshModelGetEntities')
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: dimTags
         integer(c_size_t), intent(out) :: dimTags_n
         integer(c_int), value, intent(in) :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetEntities

      !> void gmshModelGetPhysicalGroups(int **dimTags, size_t *dimTags_n, const int dim,
      !> int *ierr)
      subroutine gmshModelGetPhysicalGroups(dimTags, dimTags_n, dim, ierr) &
         bind(C, name='gmshModelGetPhysicalGroups')
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: dimTags
         integer(c_size_t), intent(out) :: dimTags_n
         integer(c_int), value, intent(in) :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalGroups

      !> void gmshModelGetEntitiesForPhysicalGroup(const int dim, const int tag, int **tags,
      !> size_t *tags_n, int *ierr)
      subroutine gmshModelGetEntitiesForPhysicalGroup(dim, tag, tags, tags_n, ierr) &
         bind(C, name='gmshModelGetEntitiesForPhysicalGroup')
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: dim, tag
         type(c_ptr), intent(out) :: tags
         integer(c_size_t), intent(out) :: tags_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetEntitiesForPhysicalGroup

      !> void gmshModelGetPhysicalGroupsForEntity(const int dim, const int tag,
      !> int **physicalTags, size_t *physicalTags_n, int *ierr)
      subroutine gmshModelGetPhysicalGroupsForEntity(dim, tag, physicalTags, physicalTags_n, &
                                                     ierr) &
         bind(C, name='gmshModelGetPhysicalGroupsForEntity')
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: dim, tag
         type(c_ptr), intent(out) :: physicalTags
         integer(c_size_t), intent(out) :: physicalTags_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalGroupsForEntity

      !> void gmshModelGetPhysicalName(const int dim, const int tag, char **name, int *ierr)
      subroutine gmshModelGetPhysicalName(dim, tag, name, ierr) &
         bind(C, name='gmshModelGetPhysicalName')
         import :: c_int, c_ptr
         integer(c_int), value, intent(in) :: dim, tag
         type(c_ptr), intent(out) :: name
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalName

      !> void gmshModelMeshGenerate(const int dim, int *ierr)
      subroutine gmshModelMeshGenerate(dim, ierr) bind(C, name='gmshModelMeshGenerate')
         import :: c_int
         integer(c_int), value, intent(in) :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGenerate

      !> void gmshModelMeshGetNodes(size_t **nodeTags, size_t *nodeTags_n, double **coord,
      !> size_t *coord_n, double **parametricCoord, size_t *parametricCoord_n, const int dim,
      !> const int tag, const int includeBoundary, const int returnParametricCoord, int *ierr)
      subroutine gmshModelMeshGetNodes(nodeTags, nodeTags_n, coord, coord_n, parametricCoord, &
                                       parametricCoord_n, dim, tag, includeBoundary, &
                                       returnParametricCoord, ierr) &
         bind(C, name='gmshModelMeshGetNodes')
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: nodeTags, coord, parametricCoord
         integer(c_size_t), intent(out) :: nodeTags_n, coord_n, parametricCoord_n
         integer(c_int), value, intent(in) :: dim, tag, includeBoundary, returnParametricCoord
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetNodes

      !> void gmshModelMeshGetElementTypes(int **elementTypes, size_t *elementTypes_n,
      !> const int dim, const int tag, int *ierr)
      subroutine gmshModelMeshGetElementTypes(elementTypes, elementTypes_n, dim, tag, ierr) &
         bind(C, name='gmshModelMeshGetElementTypes')
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: elementTypes
         integer(c_size_t), intent(out) :: elementTypes_n
         integer(c_int), value, intent(in) :: dim, tag
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementTypes

      !> void gmshModelMeshGetElementsByType(const int elementType, size_t **elementTags,
      !> size_t *elementTags_n, size_t **nodeTags, size_t *nodeTags_n, const int tag,
      !> const size_t task, const size_t numTasks, int *ierr)
      subroutine gmshModelMeshGetElementsByType(elementType, elementTags, elementTags_n, &
                                                nodeTags, nodeTags_n, tag, task, numTasks, ierr) &
         bind(C, name='gmshModelMeshGetElementsByType')
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: elementType
         type(c_ptr), intent(out) :: elementTags, nodeTags
         integer(c_size_t), intent(out) :: elementTags_n, nodeTags_n
         integer(c_int), value, intent(in) :: tag
         integer(c_size_t), value, intent(in) :: task, numTasks
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementsByType

      !> void gmshModelMeshGetElementProperties(const int elementType, char **elementName,
      !> int *dim, int *order, int *numNodes, double **localNodeCoord,
      !> size_t *localNodeCoord_n, int *numPrimaryNodes, int *ierr)
      subroutine gmshModelMeshGetElementProperties(elementType, elementName, dim, order, &
                                                   numNodes, localNodeCoord, localNodeCoord_n, &
                                                   numPrimaryNodes, ierr) &
         bind(C, name='gmshModelMeshGetElementProperties')
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value, intent(in) :: elementType
         type(c_ptr), intent(out) :: elementName
         integer(c_int), intent(out) :: dim, order, numNodes
         type(c_ptr), intent(out) :: localNodeCoord
         integer(c_size_t), intent(out) :: localNodeCoord_n
         integer(c_int), intent(out) :: numPrimaryNodes
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementProperties

      !> void gmshLoggerStart(int *ierr)
      subroutine gmshLoggerStart(ierr) bind(C, name='gmshLoggerStart')
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerStart

      !> void gmshLoggerStop(int *ierr)
      subroutine gmshLoggerStop(ierr) bind(C, name='gmshLoggerStop')
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerStop

      !> void gmshLoggerGet(char ***log, size_t *log_n, int *ierr)
      subroutine gmshLoggerGet(log, log_n, ierr) bind(C, name='gmshLoggerGet')
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: log
         integer(c_size_t), intent(out) :: log_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerGet

      !> void gmshLoggerGetLastError(char **error, int *ierr)
      subroutine gmshLoggerGetLastError(error, ierr) bind(C, name='gmshLoggerGetLastError')
         import :: c_int, c_ptr
         type(c_ptr), intent(out) :: error
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerGetLastError

   end interface

end module exic_io_gmsh_c
