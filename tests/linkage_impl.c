/* The implementation compiled as C, linked into the C++ program of
   linkage_user.cpp: checks the extern "C" linkage of the declarations. */
#define HRM_IMPLEMENTATION
#include "hrm.h"
