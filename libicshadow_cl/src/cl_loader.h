/* cl_loader.h — OpenCL's entry points, loaded on first use: the ICD loader (libOpenCL.so.1) is
 * opened with dlopen when a device is first looked for (ics_cl_load), not linked, so a program
 * that links libicshadow_cl or the renderer's cl module maps no OpenCL until it uses it, and
 * runs where OpenCL is not installed (the cl functions then say so). Included by cl_device.h
 * after CL/cl.h: each function below is called through the table, by its usual name. */
#ifndef ICS_CL_LOADER_H
#define ICS_CL_LOADER_H

#include <stddef.h>

/* every OpenCL function the library and the cl backend call */
#define ICS_CL_FUNCS(X)                                                                         \
  X(clBuildProgram) X(clCreateBuffer) X(clCreateCommandQueue) X(clCreateContext)                \
  X(clCreateKernel) X(clCreateProgramWithSource) X(clEnqueueFillBuffer)                         \
  X(clEnqueueNDRangeKernel) X(clEnqueueReadBuffer) X(clEnqueueWriteBuffer) X(clFinish)           \
  X(clGetDeviceIDs) X(clGetDeviceInfo) X(clGetEventInfo) X(clGetEventProfilingInfo)             \
  X(clGetPlatformIDs) X(clGetPlatformInfo) X(clGetProgramBuildInfo) X(clReleaseCommandQueue)    \
  X(clReleaseContext) X(clReleaseEvent) X(clReleaseKernel) X(clReleaseMemObject)                \
  X(clReleaseProgram) X(clSetKernelArg) X(clWaitForEvents)

#define ICS_CL_FIELD_(name) __typeof__(name) *name;
typedef struct ics_cl_api {
  ICS_CL_FUNCS(ICS_CL_FIELD_)
} ics_cl_api;
#undef ICS_CL_FIELD_

extern ics_cl_api ics_cl_fn; /* filled by ics_cl_load */

/* Opens the ICD loader once (thread-safe; the outcome remembered): 1, or 0 with the reason. */
int ics_cl_load(char *why, size_t why_size);

#ifndef ICS_CL_LOADER_IMPL /* calls go through the table */
#define clBuildProgram (ics_cl_fn.clBuildProgram)
#define clCreateBuffer (ics_cl_fn.clCreateBuffer)
#define clCreateCommandQueue (ics_cl_fn.clCreateCommandQueue)
#define clCreateContext (ics_cl_fn.clCreateContext)
#define clCreateKernel (ics_cl_fn.clCreateKernel)
#define clCreateProgramWithSource (ics_cl_fn.clCreateProgramWithSource)
#define clEnqueueFillBuffer (ics_cl_fn.clEnqueueFillBuffer)
#define clEnqueueNDRangeKernel (ics_cl_fn.clEnqueueNDRangeKernel)
#define clEnqueueReadBuffer (ics_cl_fn.clEnqueueReadBuffer)
#define clEnqueueWriteBuffer (ics_cl_fn.clEnqueueWriteBuffer)
#define clFinish (ics_cl_fn.clFinish)
#define clGetDeviceIDs (ics_cl_fn.clGetDeviceIDs)
#define clGetDeviceInfo (ics_cl_fn.clGetDeviceInfo)
#define clGetEventInfo (ics_cl_fn.clGetEventInfo)
#define clGetEventProfilingInfo (ics_cl_fn.clGetEventProfilingInfo)
#define clGetPlatformIDs (ics_cl_fn.clGetPlatformIDs)
#define clGetPlatformInfo (ics_cl_fn.clGetPlatformInfo)
#define clGetProgramBuildInfo (ics_cl_fn.clGetProgramBuildInfo)
#define clReleaseCommandQueue (ics_cl_fn.clReleaseCommandQueue)
#define clReleaseContext (ics_cl_fn.clReleaseContext)
#define clReleaseEvent (ics_cl_fn.clReleaseEvent)
#define clReleaseKernel (ics_cl_fn.clReleaseKernel)
#define clReleaseMemObject (ics_cl_fn.clReleaseMemObject)
#define clReleaseProgram (ics_cl_fn.clReleaseProgram)
#define clSetKernelArg (ics_cl_fn.clSetKernelArg)
#define clWaitForEvents (ics_cl_fn.clWaitForEvents)
#endif

#endif
