/**
 * @class   vtkCAONIfTIReader
 * @brief   VTK's vtkNIFTIImageReader behind a check of the file's header against its contents.
 *
 * Reads a NIfTI-1 or NIfTI-2 volume (.nii, .nii.gz) exactly as vtkNIFTIImageReader does, after cao::CheckNIfTIFile (caoFileChecks.h)
 * has compared what the header claims with what the file holds: a header
 * declaring more voxels than the kernels index (2^31 - 1) or than the file
 * can hold fails RequestInformation with one error naming the file, the
 * claim and the limit, before anything is allocated (vtkNIFTIImageReader alone aborts
 * in the allocation, or reads past its buffers). The plugin's reader proxy
 * uses this class; `cao` runs the same check.
 */
#ifndef vtkCAONIfTIReader_h
#define vtkCAONIfTIReader_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkNIFTIImageReader.h"

class CAOFILTERSAO_EXPORT vtkCAONIfTIReader : public vtkNIFTIImageReader
{
public:
  static vtkCAONIfTIReader* New();
  vtkTypeMacro(vtkCAONIfTIReader, vtkNIFTIImageReader);

protected:
  vtkCAONIfTIReader() = default;
  ~vtkCAONIfTIReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// ParaView's pipeline runs the data pass even after the information pass
  /// failed: the check again, so the superclass never allocates the claim.
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The check of the file (an error reported when it fails).
  bool CheckFile();

private:
  vtkCAONIfTIReader(const vtkCAONIfTIReader&) = delete;
  void operator=(const vtkCAONIfTIReader&) = delete;
};

#endif
