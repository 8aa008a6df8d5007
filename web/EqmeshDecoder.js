// The eqmesh WebAssembly decoder as a small JS object: stream bytes in, typed
// arrays (positions, unit normals, TEXCOORD_0 when the stream has an atlas, indices) out, errors as EqmeshError with the
// eqmesh StatusCode name. The wasm module (build-wasm/eqmesh_decoder.mjs, from
// scripts/build-wasm.sh) hands the Draco base chunk to a Draco decoder module,
// which three.js ships in examples/jsm/libs/draco/; loadDracoDecoderModule loads it.

// eqmesh::StatusCode values, for callers that switch on codes.
export const StatusCode = Object.freeze( {
	OK: 0, IO_ERROR: 1, PARSE_ERROR: 2, INVALID_ARGUMENT: 3, INVALID_MESH: 4,
	CORRUPT_STREAM: 5, UNSUPPORTED_VERSION: 6, UNSUPPORTED_FEATURE: 7, RESOURCE_LIMIT: 8, INTERNAL: 9,
} );

export class EqmeshError extends Error {

	constructor( code, codeName, message ) {

		super( `${codeName}: ${message}` );
		this.name = 'EqmeshError';
		this.code = code;
		this.codeName = codeName;

	}

}

// Loads Draco's WebIDL decoder (draco_wasm_wrapper.js + draco_decoder.wasm) from
// `path`. The wrapper is a classic script, not a module, hence the Function call;
// fetching it ourselves keeps the page free of globals.
export async function loadDracoDecoderModule( path ) {

	const base = path.endsWith( '/' ) ? path : path + '/';
	const [ wrapper, wasmBinary ] = await Promise.all( [
		fetchOk( base + 'draco_wasm_wrapper.js' ).then( ( r ) => r.text() ),
		fetchOk( base + 'draco_decoder.wasm' ).then( ( r ) => r.arrayBuffer() ),
	] );
	const factory = new Function( wrapper + '\nreturn DracoDecoderModule;' )();
	return new Promise( ( resolve ) => {

		factory( { wasmBinary, onModuleLoaded: resolve } );

	} );

}

async function fetchOk( url ) {

	const response = await fetch( url );
	if ( ! response.ok ) throw new Error( `${url}: HTTP ${response.status}` );
	return response;

}

// Decodes one Draco mesh buffer to plain arrays, or { error } (never throws past
// here: the C++ side turns the error into a CORRUPT_STREAM status).
function decodeDracoMesh( draco, bytes ) {

	const decoder = new draco.Decoder();
	const mesh = new draco.Mesh();
	try {

		const status = decoder.DecodeArrayToMesh( bytes, bytes.byteLength, mesh );
		if ( ! status.ok() || mesh.ptr === 0 ) return { error: status.error_msg() || 'not a Draco mesh' };
		return readDracoMesh( draco, decoder, mesh );

	} finally {

		draco.destroy( mesh );
		draco.destroy( decoder );

	}

}

function readDracoMesh( draco, decoder, mesh ) {

	const id = decoder.GetAttributeId( mesh, draco.POSITION );
	const attribute = id < 0 ? null : decoder.GetAttribute( mesh, id );
	if ( ! attribute || attribute.num_components() !== 3 ) return { error: 'no 3-component position attribute' };
	const positions = copyFromDraco( draco, mesh.num_points() * 3, Float32Array, ( bytes, ptr ) =>
		decoder.GetAttributeDataArrayForAllPoints( mesh, attribute, draco.DT_FLOAT32, bytes, ptr ) );
	const indices = copyFromDraco( draco, mesh.num_faces() * 3, Uint32Array, ( bytes, ptr ) =>
		decoder.GetTrianglesUInt32Array( mesh, bytes, ptr ) );
	if ( ! positions || ! indices ) return { error: 'could not read the decoded mesh' };
	return { positions, indices };

}

function copyFromDraco( draco, count, Type, fill ) {

	const bytes = count * Type.BYTES_PER_ELEMENT;
	const ptr = draco._malloc( bytes );
	try {

		if ( ! fill( bytes, ptr ) ) return null;
		return new Type( draco.HEAPF32.buffer, ptr, count ).slice();

	} finally {

		draco._free( ptr );

	}

}

// A 767-byte stream (samples/meshes/blob.obj encoded with --bpv 0.6 --levels 4, 11k
// vertices out) decoded once when a decoder is created. A page's first decode otherwise
// runs the module's baseline code, about three times slower than the optimised code V8
// compiles from it in the background once the code is hot; decoding this while the asset
// still downloads takes that cost off the first real decode.
const WARM_UP_STREAM =
	'RVFNUwEDAQAEBqsDQC5xfzjUAXbvAZkBFCtSCj1qnL8Seoi/Aw54v1/YIDv/+AG02Bd91pjtgpCmtwHBFXRL+ENrzhP5qOrm' +
	'WsNO99Di7oXnwO7PrP+mDnPQh5Jg0/99vGDlsdMv4JnJ/yoUMV8iJjk4hn70+qGBY8mckqKwcKpT589gzZvCPeFpVfZS5IOH' +
	'GPIl+cuCKKD2P1iAfqJayBEYVl9Nbgtcj0E/CHs+A2OaVTbBcg/ezKfG5NvYRj7p4CP99rpXTRkYqV8vADoNtKf0aIAv/A0S' +
	'XhgkZ13B+X9V+iUh7YeLxjkVk+QAAAAAe37fAIZ8IH5Mn9tIsI6O2oekBQ0VD41CsfF8Bok5dtjwfTwdDcworOxnEKiP7+2J' +
	'zAaprIevTHmZG/hJKpyvTixD6Ld2/NLEqfu7BsD8bGuVbK5A8yOBfYERbFBVRW3ZnLKJKWbiEBpoeaDEBYTBmrZARAAAAex9' +
	'XgCWTCGuNWQrONheBrXfApp1Xn7xtp6t3WpeRDjJ9UtVTtOd/WGCSiWCcl2/A+O6BhZiAw/w76HEWWPLJGqdqxLp5Cisn+rI' +
	'nFwKJnVWfKmfXY1AQhze9cehzk3C31qeeJgBB8XDgooO2pJIjajScVdES+4Ku6JW/6A5XuU0AOGwvQzNooaullizL8ftgko+' +
	'8tpIpwEKRvjVx3Blz+F12UySooVI5L0bC8Beu87494TVZzaY48wJLwR5vYpIc0bCDln/vdF/uSPIHrwdnm4nEh24uuB/mzNe' +
	'InfPdQJ8xH2DaTMcHE3PbKsAAAAHsHeKAKZUJAYnaE8r4Jtp0tcWC0T0CBF5xUWnAbnf2nEOSyiwyyF4AAc2eyoD5Q3N5SHH' +
	'YU7Hpp++vsqVlg0NmUvYiVw5dDj7Z1quN4RMjWzl2fMWIQMV7ncdU4KcQSeUijBghOi93hRyn9b1cLiGwJfUCiUJ1Dqch8j6' +
	'TR4H3JUHUcrmcpdjS4oiSfWKP8COBMHxQWwAAAAewGBqALZ8G3oz8GDO29QDgAA=';

export class EqmeshDecoder {

	// `createWasm`: the default export of build-wasm/eqmesh_decoder.mjs;
	// `draco`: a loaded Draco decoder module (loadDracoDecoderModule);
	// `locateFile`: where the .wasm lies when it is not beside the .mjs;
	// `wasmBinary`: the .wasm bytes, where there is nothing to fetch them from;
	// `warmUp`: decode a small built-in stream first (WARM_UP_STREAM), default true.
	static async create( { createWasm, draco, locateFile, wasmBinary, warmUp = true } ) {

		if ( ! createWasm || ! draco ) throw new Error( 'EqmeshDecoder.create needs createWasm and draco' );
		const options = { eqmeshDracoDecode: ( bytes ) => decodeDracoMesh( draco, bytes ) };
		if ( locateFile ) options.locateFile = locateFile;
		if ( wasmBinary ) options.wasmBinary = wasmBinary;
		const decoder = new EqmeshDecoder( await createWasm( options ) );
		if ( warmUp ) decoder.decode( Uint8Array.from( atob( WARM_UP_STREAM ), ( c ) => c.charCodeAt( 0 ) ) );
		return decoder;

	}

	constructor( wasm ) {

		this.wasm = wasm;

	}

	// Full stream (maxLevel -1) or the bytes up to the end of level maxLevel's chunk;
	// at most maxTriangles triangles (0: every one), refined where the surface needs
	// them and closed without cracks.
	decode( bytes, maxLevel = - 1, maxTriangles = 0 ) {

		return this._withResult( bytes, ( ptr ) => this.wasm._eqm_decode( ptr, bytes.byteLength, maxLevel, maxTriangles ),
			( r ) => ( { ...this._layout( r ), ...this._geometry( r ) } ) );

	}

	// The stream header only: levels, coder and the byte length of every chunk.
	readInfo( bytes ) {

		return this._withResult( bytes, ( ptr ) => this.wasm._eqm_read_info( ptr, bytes.byteLength ),
			( r ) => this._layout( r ) );

	}

	_withResult( bytes, call, read ) {

		const w = this.wasm;
		const ptr = w._malloc( Math.max( bytes.byteLength, 1 ) );
		w.HEAPU8.set( bytes, ptr );
		let result = 0;
		try {

			result = call( ptr );
			const code = w._eqm_status( result );
			if ( code !== StatusCode.OK ) {

				throw new EqmeshError( code, w.UTF8ToString( w._eqm_status_name( code ) ),
					w.UTF8ToString( w._eqm_message( result ) ) );

			}
			return read( result );

		} finally {

			if ( result ) w._eqm_free( result );
			w._free( ptr );

		}

	}

	_layout( r ) {

		const w = this.wasm;
		const chunkLengths = [];
		for ( let j = 0; j < w._eqm_chunk_count( r ); j ++ ) chunkLengths.push( w._eqm_chunk_length( r, j ) );
		return { levelsInStream: w._eqm_levels_in_stream( r ), coder: w._eqm_coder( r ), chunkLengths };

	}

	// Copies out of the heap: the next decode may grow (and so detach) it.
	_geometry( r ) {

		const w = this.wasm;
		const vertices = w._eqm_vertex_count( r );
		const indexCount = w._eqm_index_count( r );
		const f32 = ( ptr, n ) => new Float32Array( w.HEAPU8.buffer, ptr, n ).slice();
		const u32 = new Uint32Array( w.HEAPU8.buffer, w._eqm_indices( r ), indexCount );
		const uv = w._eqm_texcoords( r );
		return {
			levelDecoded: w._eqm_level_decoded( r ),
			positions: f32( w._eqm_positions( r ), vertices * 3 ),
			normals: f32( w._eqm_normals( r ), vertices * 3 ),
			texcoords: uv ? f32( uv, vertices * 2 ) : null,
			// ext_spec rule 6: 16-bit indices whenever the level's vertices fit.
			indices: vertices <= 65535 ? Uint16Array.from( u32 ) : u32.slice(),
		};

	}

}
