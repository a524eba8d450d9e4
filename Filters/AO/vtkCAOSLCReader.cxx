#include "vtkCAOSLCReader.h"

#include "caoFileChecks.h"
#include "vtkObjectFactory.h"

#include <string>

vtkStandardNewMacro(vtkCAOSLCReader);

//------------------------------------------------------------------------------
bool vtkCAOSLCReader::CheckFile()
{
  const char* name = this->GetFileName();
  std::string error = "no file name was given";
  if (!name || !cao::CheckSLCFile(name, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkCAOSLCReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->CheckFile())
    return 0;
  return this->Superclass::RequestInformation(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
void vtkCAOSLCReader::ExecuteDataWithInformation(vtkDataObject* output, vtkInformation* outInfo)
{
  if (this->CheckFile())
    this->Superclass::ExecuteDataWithInformation(output, outInfo);
}
