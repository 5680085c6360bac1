// This file is part of meshoptimizer library; see meshoptimizer.h for version/license details
#include "obscura_meshoptimizer.h"

void obscura_meshopt_setAllocator(void* (MESHOPTIMIZER_ALLOC_CALLCONV* allocate)(size_t), void (MESHOPTIMIZER_ALLOC_CALLCONV* deallocate)(void*))
{
	obscura_meshopt_Allocator::Storage::allocate = allocate;
	obscura_meshopt_Allocator::Storage::deallocate = deallocate;
}
