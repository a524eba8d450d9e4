#include "vtkCAONIfTIReader.h"

#include "caoFileChecks.h"
#include "vtkObjectFactory.h"

#include <string>

vtkStandardNewMacro(vtkCAONIfTIReader);

//------------------------------------------------------------------------------
bool vtkCAONIfTIReader::CheckFile()
{
  const char* name = this->GetFileName();
  std::string error = "no file name was given";
  if (!name || !cao::CheckNIfTIFile(name, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkCAONIfTIReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->CheckFile())
    return 0;
  return this->Superclass::RequestInformation(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkCAONIfTIReader::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->CheckFile())
    return 0;
  return this->Superclass::RequestData(request, inputVector, outputVector);
}
