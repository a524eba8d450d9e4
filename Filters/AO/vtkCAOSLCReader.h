/**
 * @class   vtkCAOSLCReader
 * @brief   VTK's vtkSLCReader behind a check of the file's header against its contents.
 *
 * Reads an SLC volume exactly as vtkSLCReader does, after cao::CheckSLCFile (caoFileChecks.h)
 * has compared what the header claims with what the file holds: a header
 * declaring more voxels than the kernels index (2^31 - 1) or than the file
 * can hold fails RequestInformation with one error naming the file, the
 * claim and the limit, before anything is allocated (vtkSLCReader alone aborts
 * in the allocation, or reads past its buffers). The plugin's reader proxy
 * uses this class; `cao` runs the same check.
 */
#ifndef vtkCAOSLCReader_h
#define vtkCAOSLCReader_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkSLCReader.h"

class CAOFILTERSAO_EXPORT vtkCAOSLCReader : public vtkSLCReader
{
public:
  static vtkCAOSLCReader* New();
  vtkTypeMacro(vtkCAOSLCReader, vtkSLCReader);

protected:
  vtkCAOSLCReader() = default;
  ~vtkCAOSLCReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// ParaView's pipeline runs the data pass even after the information pass
  /// failed: the check again, so the superclass never allocates the claim.
  void ExecuteDataWithInformation(vtkDataObject* output, vtkInformation* outInfo) override;

  /// The check of the file (an error reported when it fails).
  bool CheckFile();

private:
  vtkCAOSLCReader(const vtkCAOSLCReader&) = delete;
  void operator=(const vtkCAOSLCReader&) = delete;
};

#endif
